#include "runtime/parameters.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace ltm::runtime {
namespace {

std::vector<std::string> split_dots(const std::string& key) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t dot = key.find('.', start);
        parts.push_back(key.substr(start, dot - start));
        if (dot == std::string::npos) return parts;
        start = dot + 1;
    }
}

// Every leaf key of a map, dotted; a nested map contributes its own leaves.
void leaves(const YAML::Node& node, const std::string& prefix,
            std::vector<std::pair<std::string, YAML::Node>>& out) {
    for (const auto& kv : node) {
        const std::string k =
            prefix.empty() ? kv.first.as<std::string>() : prefix + "." + kv.first.as<std::string>();
        if (kv.second.IsMap() && kv.second.size() > 0) {
            leaves(kv.second, k, out);
        } else {
            out.emplace_back(k, kv.first);
        }
    }
}

// The node at parts[i..] below `node`. A key may itself hold dots: `keyframe.distance: 1` is the
// same parameter as `keyframe: {distance: 1}` (leaves() reports both as "keyframe.distance").
// *key_line: the line of the last key on the way.
YAML::Node find_dotted(const YAML::Node& node, const std::vector<std::string>& parts, std::size_t i,
                       int* key_line) {
    if (i == parts.size()) return node;
    if (!node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
    for (const auto& kv : node) {
        const std::string k = kv.first.as<std::string>();
        std::string joined;
        for (std::size_t j = i; j < parts.size() && joined.size() < k.size(); ++j) {
            joined += (j > i ? "." : "") + parts[j];
            if (joined != k) continue;
            int line = kv.first.Mark().line + 1;
            const YAML::Node found = find_dotted(kv.second, parts, j + 1, &line);
            if (found.IsDefined()) {
                *key_line = line;
                return found;
            }
        }
    }
    return YAML::Node(YAML::NodeType::Undefined);
}

}  // namespace

void check_plain_keys(const YAML::Node& node, const std::string& file) {
    if (node.IsSequence()) {
        for (const auto& e : node) check_plain_keys(e, file);
    } else if (node.IsMap()) {
        for (const auto& kv : node) {
            if (!kv.first.IsScalar())
                throw ConfigError(file, kv.first.Mark().line + 1, "yaml",
                                  "a key must be plain text");
            check_plain_keys(kv.second, file);
        }
    }
}

std::string expand_env(const std::string& text) {
    std::string out;
    std::size_t i = 0;
    while (i < text.size()) {
        if (text[i] == '$' && i + 1 < text.size() && text[i + 1] == '{') {
            const std::size_t end = text.find('}', i + 2);
            if (end == std::string::npos) break;
            std::string inner = text.substr(i + 2, end - i - 2), fallback;
            const std::size_t dflt = inner.find(":-");
            if (dflt != std::string::npos) {
                fallback = inner.substr(dflt + 2);
                inner = inner.substr(0, dflt);
            }
            const char* v = std::getenv(inner.c_str());
            out += (v && *v) ? std::string(v) : fallback;
            i = end + 1;
        } else {
            out += text[i++];
        }
    }
    if (i < text.size()) out += text.substr(i);
    return out;
}

Parameters::Parameters(YAML::Node node, std::string file, std::string prefix)
    : root_(node),
      file_(std::move(file)),
      prefix_(std::move(prefix)),
      used_(std::make_shared<std::set<std::string>>()) {
    if (root_.IsDefined() && !root_.IsNull() && !root_.IsMap())
        throw ConfigError(file_, root_.Mark().line + 1, prefix_, "parameters must be a map");
}

Parameters Parameters::from_file(const std::string& path, const std::string& prefix) {
    if (!std::filesystem::is_regular_file(path)) throw ConfigError(path, 0, prefix, "no such file");
    try {
        const YAML::Node root = YAML::LoadFile(path);
        check_plain_keys(root, path);
        return Parameters(root, path, prefix);
    } catch (const YAML::ParserException& e) {
        throw ConfigError(path, e.mark.line + 1, prefix, e.msg);
    }
}

YAML::Node Parameters::lookup(const std::string& key) const {
    // Const access only: a non-const operator[] would insert the key into the config.
    int line = 0;
    return find_dotted(root_, split_dots(key), 0, &line);
}

bool Parameters::has(const std::string& key) const {
    const YAML::Node n = lookup(key);
    return n.IsDefined() && !n.IsNull();
}

int Parameters::line_of(const std::string& key) const {
    // Line of the key itself (not of its value) when present, else of the params map.
    const YAML::Node cur = root_;
    if (!cur.IsDefined() || cur.IsNull()) return 0;
    int line = cur.Mark().line + 1;
    if (find_dotted(root_, split_dots(key), 0, &line).IsDefined()) return line;
    YAML::Node node;
    node.reset(root_);
    for (const auto& part : split_dots(key)) {
        if (!node.IsMap()) break;
        bool found = false;
        for (const auto& kv : node) {
            if (kv.first.as<std::string>() == part) {
                line = kv.first.Mark().line + 1;
                node.reset(kv.second);
                found = true;
                break;
            }
        }
        if (!found) break;
    }
    return line;
}

void Parameters::fail(const std::string& key, const std::string& problem) const {
    throw ConfigError(file_, line_of(key), full(key), problem);
}

std::string Parameters::path(const std::string& key, const std::string& fallback, PathCheck check) {
    std::string p = get<std::string>(key, fallback);
    if (p.empty()) return p;
    namespace fs = std::filesystem;
    switch (check) {
        case PathCheck::kNone:
            break;
        case PathCheck::kFileExists:
            if (!fs::is_regular_file(p)) fail(key, "no such file: " + p);
            break;
        case PathCheck::kDirExists:
            if (!fs::is_directory(p)) fail(key, "no such folder: " + p);
            break;
        case PathCheck::kParentExists: {
            const fs::path parent = fs::path(p).parent_path();
            if (!parent.empty() && !fs::is_directory(parent)) {
                std::error_code ec;
                fs::create_directories(parent, ec);
                if (ec) fail(key, "cannot create folder " + parent.string() + ": " + ec.message());
            }
            break;
        }
    }
    return p;
}

namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] =
                std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

// The known keys for an unknown one: all of them when few, else the closest few.
std::string known_keys(const std::string& unknown, const std::set<std::string>& known) {
    constexpr std::size_t kListAll = 12, kClosest = 3;
    std::string out;
    if (known.size() <= kListAll) {
        for (const auto& k : known) out += (out.empty() ? "" : ", ") + k;
        return " (known: " + out + ")";
    }
    std::vector<std::pair<std::size_t, std::string>> ranked;
    for (const auto& k : known) ranked.push_back({edit_distance(unknown, k), k});
    std::sort(ranked.begin(), ranked.end());
    for (std::size_t i = 0; i < kClosest; ++i) out += (out.empty() ? "" : ", ") + ranked[i].second;
    return " (closest of " + std::to_string(known.size()) + " known: " + out + ")";
}

}  // namespace

void Parameters::check_all_used() const {
    if (!root_.IsDefined() || root_.IsNull()) return;
    std::vector<std::pair<std::string, YAML::Node>> all;
    leaves(root_, "", all);
    std::set<std::string> seen;
    for (const auto& [key, node] : all) {
        if (!seen.insert(key).second)
            throw ConfigError(file_, node.Mark().line + 1, full(key),
                              "given twice (as a dotted key and nested)");
        if (used_->count(key)) continue;
        throw ConfigError(
            file_, line_of(key), full(key),
            "unknown parameter" + (used_->empty() ? std::string(" (this component takes none)")
                                                  : known_keys(key, *used_)));
    }
}

}  // namespace ltm::runtime
