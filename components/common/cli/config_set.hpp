#pragma once
// `--set KEY=VALUE` for the benchmarks: overrides a config's keys through its visit_fields list,
// so only keys the config declares are accepted and each value is parsed as its field's type.
// Rules are checked afterwards by the config's validate() (the caller's constructor does it).
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/core/config_check.hpp"

namespace ltm::common::cli {

// The visitor that sets one key (numbers, switches, text).
struct ConfigKeySetter {
    std::string key, value;
    bool found = false;
    template <class Rule>
    void operator()(const std::string& k, double& v, const Rule&) {
        number(k, v);
    }
    template <class Rule>
    void operator()(const std::string& k, int& v, const Rule&) {
        number(k, v);
    }
    template <class Rule>
    void operator()(const std::string& k, std::string& v, const Rule&) {
        if (k != key) return;
        found = true;
        v = value;
    }
    template <class Rule>
    void operator()(const std::string& k, bool& v, const Rule&) {
        if (k != key) return;
        found = true;
        if (value != "true" && value != "false")
            throw ConfigError(key, "must be true or false (got " + value + ")");
        v = value == "true";
    }
    // A key that is unset unless given (its value then derived from the data).
    template <class T, class Rule>
    void operator()(const std::string& k, std::optional<T>& v, const Rule& rule) {
        if (k != key) return;
        T x{};
        (*this)(k, x, rule);
        v = x;
    }
    template <class T>
    void number(const std::string& k, T& v) {
        if (k != key) return;
        found = true;
        std::istringstream in(value);
        T x{};
        if (!(in >> x) || !in.eof()) throw ConfigError(key, "must be a number (got " + value + ")");
        v = x;
    }
};

namespace detail {
// visit_fields(config, prefix, visitor), or visit_fields(config, visitor) for configs without one.
template <class Config, class Visitor>
auto visit_keys(Config& c, Visitor& v, int) -> decltype(visit_fields(c, std::string(), v), void()) {
    visit_fields(c, std::string(), v);
}
template <class Config, class Visitor>
void visit_keys(Config& c, Visitor& v, long) {
    visit_fields(c, v);
}
}  // namespace detail

// Applies every "KEY=VALUE" of `sets` to `config`; `example` names a key for the error of an
// unknown one. Throws UsageError (--set) for a malformed or unknown key, ConfigError for a value
// of the wrong type.
template <class Config>
void apply_config_sets(Config& config, const std::vector<std::string>& sets,
                       const std::string& what, const std::string& example) {
    for (const std::string& kv : sets) {
        const std::size_t eq = kv.find('=');
        if (eq == std::string::npos) throw UsageError("--set", kv + ": expected KEY=VALUE");
        ConfigKeySetter s{kv.substr(0, eq), kv.substr(eq + 1)};
        detail::visit_keys(config, s, 0);
        if (!s.found)
            throw UsageError("--set", kv + ": unknown key " + s.key + " (a key of " + what +
                                          ", e.g. " + example + ")");
    }
}

}  // namespace ltm::common::cli
