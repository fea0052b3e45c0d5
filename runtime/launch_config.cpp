#include "runtime/launch_config.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "runtime/config_error.hpp"
#include "runtime/parameters.hpp"

namespace ltm::runtime {
namespace {

int line_of(const YAML::Node& n) { return n.Mark().line + 1; }

// Line of `key` inside map `map` (the key, not the value).
int key_line(const YAML::Node& map, const std::string& key) {
    for (const auto& kv : map)
        if (kv.first.as<std::string>() == key) return kv.first.Mark().line + 1;
    return line_of(map);
}

void check_keys(const std::string& file, const YAML::Node& map, const std::string& where,
                const std::set<std::string>& known) {
    for (const auto& kv : map) {
        const std::string k = kv.first.as<std::string>();
        if (!known.count(k)) {
            std::string list;
            for (const auto& s : known) list += (list.empty() ? "" : ", ") + s;
            throw ConfigError(file, kv.first.Mark().line + 1, where.empty() ? k : where + "." + k,
                              "unknown key (known: " + list + ")");
        }
    }
}

template <class T>
T scalar(const std::string& file, const YAML::Node& map, const std::string& key,
         const std::string& where, const T& fallback) {
    const YAML::Node& cmap = map;
    const YAML::Node n = cmap[key];
    if (!n.IsDefined() || n.IsNull()) return fallback;
    try {
        if (!n.IsScalar()) throw YAML::Exception(n.Mark(), "");
        return n.as<T>();
    } catch (const YAML::Exception&) {
        throw ConfigError(file, key_line(map, key), where.empty() ? key : where + "." + key,
                          std::string("expected ") + yaml_type_name<T>());
    }
}

std::vector<std::string> string_list(const std::string& file, const YAML::Node& map,
                                     const std::string& key, const std::string& where) {
    const YAML::Node& cmap = map;
    const YAML::Node n = cmap[key];
    std::vector<std::string> out;
    if (!n.IsDefined() || n.IsNull()) return out;
    if (!n.IsSequence())
        throw ConfigError(file, key_line(map, key), where + "." + key,
                          "expected a list of strings");
    for (const auto& e : n) {
        if (!e.IsScalar())
            throw ConfigError(file, line_of(e), where + "." + key, "expected a list of strings");
        out.push_back(e.as<std::string>());
    }
    return out;
}

// The scalar value of `key` in `map`, "" when absent (iterates: no zombie nodes).
std::string map_scalar(const YAML::Node& map, const std::string& key) {
    if (!map.IsMap()) return "";
    for (const auto& kv : map)
        if (kv.first.as<std::string>() == key && kv.second.IsScalar())
            return kv.second.as<std::string>();
    return "";
}

void set_dotted(YAML::Node node, const std::string& dotted, const YAML::Node& value) {
    const std::size_t dot = dotted.find('.');
    if (dot == std::string::npos) {
        node[dotted] = value;
        return;
    }
    YAML::Node child = node[dotted.substr(0, dot)];
    if (!child.IsMap()) child = YAML::Node(YAML::NodeType::Map);
    set_dotted(child, dotted.substr(dot + 1), value);
    node[dotted.substr(0, dot)] = child;
}

void apply_override(YAML::Node root, const std::string& arg) {
    const std::size_t eq = arg.find('=');
    if (eq == std::string::npos || eq == 0)
        throw ConfigError("<command line>", 0, "--set " + arg, "expected KEY=VALUE");
    const std::string key = arg.substr(0, eq);
    YAML::Node value;
    try {
        value = YAML::Load(arg.substr(eq + 1));
    } catch (const YAML::Exception& e) {
        throw ConfigError("<command line>", 0, "--set " + key, "value is not valid YAML");
    }
    check_plain_keys(value, "<command line>");
    const std::size_t dot = key.find('.');
    const YAML::Node& croot = root;
    const YAML::Node comps = croot["components"];  // invalid (not just undefined) when missing
    if (dot != std::string::npos && comps.IsDefined() && comps.IsSequence()) {
        const std::string comp = key.substr(0, dot);
        for (auto entry : comps) {
            // A component's name defaults to its type.
            std::string name = map_scalar(entry, "name");
            if (name.empty()) name = map_scalar(entry, "type");
            if (!name.empty() && name == comp) {  // ("" is an entry that is not a map)
                // NAME.remap.FROM=TO: a topic remap of the component, not a parameter.
                const std::string rest = key.substr(dot + 1);
                if (rest.rfind("remap.", 0) == 0 && rest.size() > 6) {
                    if (!value.IsScalar())
                        throw ConfigError("<command line>", 0, "--set " + key,
                                          "expected a topic name");
                    YAML::Node remap = entry["remap"];
                    if (!remap.IsMap()) {
                        remap = YAML::Node(YAML::NodeType::Map);
                        entry["remap"] = remap;
                    }
                    entry["remap"][rest.substr(6)] = value;
                    return;
                }
                YAML::Node params = entry["params"];
                if (!params.IsMap()) {
                    params = YAML::Node(YAML::NodeType::Map);
                    entry["params"] = params;
                }
                set_dotted(entry["params"], key.substr(dot + 1), value);
                return;
            }
        }
    }
    if (const YAML::Node top = croot[key.substr(0, dot == std::string::npos ? key.size() : dot)];
        dot != std::string::npos && !(top.IsDefined() && top.IsMap()) &&
        key.compare(0, 4, "dds.") != 0)  // dds.security=... on a config with Cyclone defaults
        throw ConfigError("<command line>", 0, "--set " + key,
                          "no component named '" + key.substr(0, dot) + "' in the launch config");
    set_dotted(root, key, value);
}

QosProfile load_profile(const std::string& file, const YAML::Node& n, const std::string& where,
                        QosProfile p) {
    if (!n.IsMap()) throw ConfigError(file, line_of(n), where, "expected a map");
    check_keys(file, n, where,
               {"reliable", "transient_local", "keep_all", "depth", "max_blocking_s"});
    p.reliable = scalar<bool>(file, n, "reliable", where, p.reliable);
    p.transient_local = scalar<bool>(file, n, "transient_local", where, p.transient_local);
    p.keep_all = scalar<bool>(file, n, "keep_all", where, p.keep_all);
    p.depth = scalar<int>(file, n, "depth", where, p.depth);
    p.max_blocking_s = scalar<double>(file, n, "max_blocking_s", where, p.max_blocking_s);
    if (p.depth < 1)
        throw ConfigError(file, key_line(n, "depth"), where + ".depth", "must be at least 1");
    if (p.max_blocking_s <= 0)
        throw ConfigError(file, key_line(n, "max_blocking_s"), where + ".max_blocking_s",
                          "must be positive");
    return p;
}

// `dds.security`: every file named, ${VAR}s expanded, made absolute and checked to exist.
DdsSecurity load_security(const std::string& file, const YAML::Node& dds, const YAML::Node& sec) {
    const std::string where = "dds.security";
    if (!sec.IsMap()) throw ConfigError(file, key_line(dds, "security"), where, "expected a map");
    const std::pair<const char*, std::string DdsSecurity::*> keys[] = {
        {"identity_ca", &DdsSecurity::identity_ca},
        {"certificate", &DdsSecurity::certificate},
        {"private_key", &DdsSecurity::private_key},
        {"permissions_ca", &DdsSecurity::permissions_ca},
        {"governance", &DdsSecurity::governance},
        {"permissions", &DdsSecurity::permissions}};
    std::set<std::string> known;
    for (const auto& k : keys) known.insert(k.first);
    check_keys(file, sec, where, known);
    DdsSecurity out;
    for (const auto& [key, member] : keys) {
        const std::string raw = scalar<std::string>(file, sec, key, where, "");
        const std::string path = expand_env(raw);
        if (path.empty())
            throw ConfigError(file, line_of(sec), where + "." + key,
                              "missing (a file; launch_configs/security/make_site_certs.sh "
                              "makes them)");
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec))
            throw ConfigError(file, key_line(sec, key), where + "." + key,
                              "no such file: " + path + (raw != path ? " (" + raw + ")" : ""));
        out.*member = std::filesystem::absolute(path, ec).lexically_normal().string();
    }
    return out;
}

// "1344", "1344 B", "64 KiB", "8 MiB", "1.5 MB" (SI kB/MB, binary KiB/MiB) -> bytes; false when
// the text is not a size.
bool parse_size(const std::string& text, std::int64_t& bytes) {
    std::size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        return false;
    }
    std::string unit = text.substr(used);
    unit.erase(0, unit.find_first_not_of(' '));
    static const std::pair<const char*, double> units[] = {
        {"", 1}, {"B", 1}, {"kB", 1e3}, {"KiB", 1024}, {"MB", 1e6}, {"MiB", 1048576}};
    for (const auto& [name, factor] : units) {
        if (unit != name) continue;
        const double b = value * factor;
        if (!std::isfinite(b) || b < 0 || b > 1e15 || b != std::floor(b)) return false;
        bytes = static_cast<std::int64_t>(b);
        return true;
    }
    return false;
}

// True when `key` is in `map` with a value (not null).
bool given(const YAML::Node& map, const std::string& key) {
    const YAML::Node n = map[key];
    return n.IsDefined() && !n.IsNull();
}

// An optional size in bytes within [min, max].
std::optional<std::int64_t> size_key(const std::string& file, const YAML::Node& map,
                                     const std::string& key, std::int64_t min, std::int64_t max) {
    if (!given(map, key)) return std::nullopt;
    const std::string text = scalar<std::string>(file, map, key, "dds", "");
    std::int64_t bytes = 0;
    if (!parse_size(text, bytes))
        throw ConfigError(file, key_line(map, key), "dds." + key,
                          "expected a size in bytes (1344, 64 KiB, 8 MiB), got '" + text + "'");
    if (bytes < min || bytes > max)
        throw ConfigError(file, key_line(map, key), "dds." + key,
                          "must be " + std::to_string(min) + ".." + std::to_string(max) +
                              " bytes, got " + std::to_string(bytes));
    return bytes;
}

// An optional duration [s] within [min, max].
std::optional<double> seconds_key(const std::string& file, const YAML::Node& map,
                                  const std::string& key, double min, double max) {
    if (!given(map, key)) return std::nullopt;
    const double s = scalar<double>(file, map, key, "dds", 0.0);
    if (!(s >= min && s <= max)) {
        char range[64];
        std::snprintf(range, sizeof range, "must be %g..%g s", min, max);
        throw ConfigError(file, key_line(map, key), "dds." + key, range);
    }
    return s;
}

// The Cyclone tuning keys of `dds:` (DdsSettings), checked against Cyclone 0.10's limits.
void load_dds_tuning(const std::string& f, const YAML::Node& dds, DdsSettings& d) {
    const std::int64_t kMax = std::int64_t{1} << 31;
    // Cyclone refuses fragments over 65000 B; under ~512 B the headers dominate.
    d.fragment_size = size_key(f, dds, "fragment_size", 512, 65000);
    d.max_message_size = size_key(f, dds, "max_message_size", 512, 65500);
    d.max_retransmit_message_size = size_key(f, dds, "max_retransmit_message_size", 512, 65500);
    if (d.fragment_size && d.max_message_size && *d.fragment_size > *d.max_message_size)
        throw ConfigError(
            f, key_line(dds, "fragment_size"), "dds.fragment_size",
            "must not exceed dds.max_message_size (" + std::to_string(*d.max_message_size) + " B)");
    d.socket_receive_buffer_size = size_key(f, dds, "socket_receive_buffer_size", 65536, kMax);
    d.socket_send_buffer_size = size_key(f, dds, "socket_send_buffer_size", 65536, kMax);
    // Cyclone's own bounds of the heartbeat interval (its min and max attributes: 5 ms, 8 s).
    d.heartbeat_interval_s = seconds_key(f, dds, "heartbeat_interval_s", 0.005, 8.0);
    d.nack_delay_s = seconds_key(f, dds, "nack_delay_s", 0.0, 10.0);
    d.writer_linger_s = seconds_key(f, dds, "writer_linger_s", 0.0, 3600.0);
    if (given(dds, "retransmit_merging")) {
        const std::string merging = scalar<std::string>(f, dds, "retransmit_merging", "dds", "");
        if (merging != "never" && merging != "adaptive" && merging != "always")
            throw ConfigError(f, key_line(dds, "retransmit_merging"), "dds.retransmit_merging",
                              "expected never, adaptive or always, got '" + merging + "'");
        d.retransmit_merging = merging;
    }
    d.whc_low = size_key(f, dds, "whc_low", 0, kMax);
    d.whc_high = size_key(f, dds, "whc_high", 1, kMax);
    d.whc_high_init = size_key(f, dds, "whc_high_init", 0, kMax);
    if (given(dds, "whc_adaptive"))
        d.whc_adaptive = scalar<bool>(f, dds, "whc_adaptive", "dds", true);
    // Cyclone refuses the domain unless low <= high_init <= high and low < high ("Invalid
    // watermark settings"); checked here with its defaults for the ones not given.
    const std::int64_t low = d.whc_low.value_or(1024), high = d.whc_high.value_or(500 * 1024),
                       init = d.whc_high_init.value_or(30 * 1024);
    if (!(low < high && low <= init && init <= high)) {
        const char* key = d.whc_high_init ? "whc_high_init" : d.whc_high ? "whc_high" : "whc_low";
        throw ConfigError(f, key_line(dds, key), std::string("dds.") + key,
                          "expected whc_low <= whc_high_init <= whc_high and whc_low < whc_high "
                          "(Cyclone's defaults 1 KiB, 30 KiB, 500 KiB for those not given), got " +
                              std::to_string(low) + ", " + std::to_string(init) + ", " +
                              std::to_string(high) + " B");
    }
}

// A `topics:` entry: `name: role`, or `name: {role: ..., reliable: ..., depth: ...}` (the keys of
// a `qos:` profile; each one given replaces the role's).
TopicQos load_topic_qos(const std::string& file, const YAML::Node& key, const YAML::Node& n) {
    const std::string where = "topics." + key.as<std::string>();
    const std::string roles = "sensor, state, map or stream";
    TopicQos q;
    TopicRole r;
    if (n.IsScalar()) {
        if (!parse_role(n.as<std::string>(), r))
            throw ConfigError(file, key.Mark().line + 1, where, "expected a role: " + roles);
        q.role = r;
        return q;
    }
    if (!n.IsMap())
        throw ConfigError(file, key.Mark().line + 1, where,
                          "expected a role (" + roles + ") or a map of role and qos keys");
    check_keys(file, n, where,
               {"role", "reliable", "transient_local", "keep_all", "depth", "max_blocking_s"});
    if (given(n, "role")) {
        const std::string role = scalar<std::string>(file, n, "role", where, "");
        if (!parse_role(role, r))
            throw ConfigError(file, key_line(n, "role"), where + ".role",
                              "expected " + roles + ", got '" + role + "'");
        q.role = r;
    }
    if (given(n, "reliable")) q.reliable = scalar<bool>(file, n, "reliable", where, true);
    if (given(n, "transient_local"))
        q.transient_local = scalar<bool>(file, n, "transient_local", where, false);
    if (given(n, "keep_all")) q.keep_all = scalar<bool>(file, n, "keep_all", where, false);
    if (given(n, "depth")) {
        q.depth = scalar<int>(file, n, "depth", where, 1);
        if (*q.depth < 1)
            throw ConfigError(file, key_line(n, "depth"), where + ".depth", "must be at least 1");
    }
    if (given(n, "max_blocking_s")) {
        q.max_blocking_s = scalar<double>(file, n, "max_blocking_s", where, 1.0);
        if (!(*q.max_blocking_s > 0))
            throw ConfigError(file, key_line(n, "max_blocking_s"), where + ".max_blocking_s",
                              "must be positive");
    }
    return q;
}

}  // namespace

LaunchConfig load_launch_config(const std::string& path,
                                const std::vector<std::string>& overrides) {
    LaunchConfig cfg;
    cfg.file = path;
    if (!std::filesystem::is_regular_file(path))
        throw ConfigError(path, 0, "launch config", "no such file");
    YAML::Node root;
    try {
        root = YAML::LoadFile(path);
    } catch (const YAML::ParserException& e) {
        throw ConfigError(path, e.mark.line + 1, "yaml", e.msg);
    } catch (const YAML::Exception& e) {
        throw ConfigError(path, 0, "yaml", e.what());
    }
    if (!root.IsMap())
        throw ConfigError(path, 1, "launch config", "expected a map at the top level");
    check_plain_keys(root, path);
    for (const auto& o : overrides) apply_override(root, o);
    const std::string& f = path;
    const YAML::Node& croot = root;  // const access: a missing key must not be inserted
    check_keys(f, root, "",
               {"domain_id", "namespace", "dds", "qos", "topics", "on_component_error",
                "max_restarts", "exit_when_sources_done", "idle_exit_s", "shutdown_timeout_s",
                "finish_timeout_s", "log", "components"});

    cfg.domain_id = scalar<int>(f, root, "domain_id", "", 0);
    if (cfg.domain_id < 0 || cfg.domain_id > 232)
        throw ConfigError(f, key_line(root, "domain_id"), "domain_id", "must be 0..232");
    cfg.ns = scalar<std::string>(f, root, "namespace", "", "");
    cfg.max_restarts = scalar<int>(f, root, "max_restarts", "", 3);
    cfg.exit_when_sources_done = scalar<bool>(f, root, "exit_when_sources_done", "", true);
    cfg.idle_exit_s = scalar<double>(f, root, "idle_exit_s", "", 0.0);
    cfg.shutdown_timeout_s = scalar<double>(f, root, "shutdown_timeout_s", "", 30.0);
    cfg.finish_timeout_s = scalar<double>(f, root, "finish_timeout_s", "", 60.0);
    const std::string policy = scalar<std::string>(f, root, "on_component_error", "", "stop");
    if (policy == "stop") {
        cfg.on_error = ErrorPolicy::kStop;
    } else if (policy == "restart") {
        cfg.on_error = ErrorPolicy::kRestart;
    } else {
        throw ConfigError(f, key_line(root, "on_component_error"), "on_component_error",
                          "expected 'stop' or 'restart', got '" + policy + "'");
    }

    if (const YAML::Node dds = croot["dds"]; dds.IsDefined() && !dds.IsNull()) {
        if (!dds.IsMap()) throw ConfigError(f, line_of(dds), "dds", "expected a map");
        check_keys(f, dds, "dds",
                   {"interfaces", "peers", "multicast", "max_participant_index", "extra_xml",
                    "security", "fragment_size", "max_message_size", "max_retransmit_message_size",
                    "socket_receive_buffer_size", "socket_send_buffer_size", "heartbeat_interval_s",
                    "nack_delay_s", "retransmit_merging", "whc_low", "whc_high", "whc_high_init",
                    "whc_adaptive", "writer_linger_s"});
        cfg.dds.custom = true;
        cfg.dds.interfaces = string_list(f, dds, "interfaces", "dds");
        cfg.dds.peers = string_list(f, dds, "peers", "dds");
        cfg.dds.multicast = scalar<bool>(f, dds, "multicast", "dds", true);
        cfg.dds.max_participant_index = scalar<int>(f, dds, "max_participant_index", "dds", 20);
        cfg.dds.extra_xml = scalar<std::string>(f, dds, "extra_xml", "dds", "");
        if (const YAML::Node sec = dds["security"]; sec.IsDefined() && !sec.IsNull())
            cfg.dds.security = load_security(f, dds, sec);
        load_dds_tuning(f, dds, cfg.dds);
    }

    if (const YAML::Node log = croot["log"]; log.IsDefined() && !log.IsNull()) {
        if (!log.IsMap()) throw ConfigError(f, line_of(log), "log", "expected a map");
        check_keys(f, log, "log", {"file", "max_mb", "keep"});
        cfg.log.file = expand_env(scalar<std::string>(f, log, "file", "log", ""));
        cfg.log.max_mb = scalar<double>(f, log, "max_mb", "log", cfg.log.max_mb);
        cfg.log.keep = scalar<int>(f, log, "keep", "log", cfg.log.keep);
        cfg.log_line = line_of(log);
        if (cfg.log.file.empty())
            throw ConfigError(f, cfg.log_line, "log.file", "required: the host's log file");
        if (!(cfg.log.max_mb > 0))
            throw ConfigError(f, key_line(log, "max_mb"), "log.max_mb", "must be > 0");
        if (cfg.log.keep < 0)
            throw ConfigError(f, key_line(log, "keep"), "log.keep", "must be >= 0");
    }

    for (TopicRole r : {TopicRole::kSensor, TopicRole::kState, TopicRole::kMap, TopicRole::kStream})
        cfg.qos[r] = default_profile(r);
    if (const YAML::Node qos = croot["qos"]; qos.IsDefined() && !qos.IsNull()) {
        if (!qos.IsMap()) throw ConfigError(f, line_of(qos), "qos", "expected a map");
        check_keys(f, qos, "qos", {"sensor", "state", "map", "stream"});
        for (const auto& kv : qos) {
            TopicRole r;
            parse_role(kv.first.as<std::string>(), r);
            cfg.qos[r] =
                load_profile(f, kv.second, "qos." + kv.first.as<std::string>(), cfg.qos[r]);
        }
    }
    if (const YAML::Node topics = croot["topics"]; topics.IsDefined() && !topics.IsNull()) {
        if (!topics.IsMap())
            throw ConfigError(f, line_of(topics), "topics",
                              "expected a map of name: role or name: {role: ..., reliable: ...}");
        // Names are resolved against the namespace by the host.
        for (const auto& kv : topics)
            cfg.topics[kv.first.as<std::string>()] = load_topic_qos(f, kv.first, kv.second);
    }

    const YAML::Node comps = croot["components"];
    if (!comps.IsDefined() || !comps.IsSequence() || comps.size() == 0)
        throw ConfigError(f, comps.IsDefined() ? line_of(comps) : 1, "components",
                          "expected a non-empty list of components");
    std::set<std::string> names;
    for (const auto& entry : comps) {
        if (!entry.IsMap())
            throw ConfigError(f, line_of(entry), "components", "each entry must be a map");
        check_keys(f, entry, "components[]", {"name", "type", "params", "remap"});
        ComponentSpec spec;
        spec.line = line_of(entry);
        spec.type = scalar<std::string>(f, entry, "type", "components[]", "");
        spec.type_line = key_line(entry, "type");
        if (spec.type.empty()) throw ConfigError(f, spec.line, "components[].type", "missing");
        spec.name = scalar<std::string>(f, entry, "name", "components[]", spec.type);
        if (!names.insert(spec.name).second)
            throw ConfigError(f, key_line(entry, "name"), spec.name,
                              "two components with this name");
        if (const YAML::Node params = entry["params"]; params.IsDefined())
            spec.params.reset(params);
        if (const YAML::Node remap = entry["remap"]; remap.IsDefined() && !remap.IsNull()) {
            if (!remap.IsMap())
                throw ConfigError(f, line_of(remap), spec.name + ".remap",
                                  "expected a map of from: to");
            for (const auto& kv : remap) {
                const std::string from = kv.first.as<std::string>();
                if (!kv.second.IsScalar())
                    throw ConfigError(f, kv.first.Mark().line + 1, spec.name + ".remap." + from,
                                      "expected a topic name");
                spec.remaps[from] = kv.second.as<std::string>();
                spec.remap_lines[from] = kv.first.Mark().line + 1;
            }
        }
        cfg.components.push_back(std::move(spec));
    }
    return cfg;
}

}  // namespace ltm::runtime
