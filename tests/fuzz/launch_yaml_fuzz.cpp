// Fuzz target: launch configs (runtime/launch_config) and the component parameters read from
// them (runtime/parameters). The input is the YAML file; its lines that start with "#set " are
// also passed as --set overrides (they are comments to YAML). Most leaves of every component's
// params are then read as each type a component may ask for, and the unread keys are checked.
// Promise: a LaunchConfig or a one-line ConfigError, and the same for every parameter read.
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_util.hpp"
#include "runtime/config_error.hpp"
#include "runtime/launch_config.hpp"
#include "runtime/parameters.hpp"

using ltm::runtime::ConfigError;

namespace {

// Dotted keys of the scalar-keyed leaves of `node` (at most 64, depth 8).
void leaf_keys(const YAML::Node& node, const std::string& prefix, int depth,
               std::vector<std::string>& out) {
    if (!node.IsMap() || depth > 8) return;
    for (const auto& kv : node) {
        if (out.size() >= 64) return;
        if (!kv.first.IsScalar()) continue;
        const std::string key =
            prefix.empty() ? kv.first.Scalar() : prefix + "." + kv.first.Scalar();
        if (kv.second.IsMap() && kv.second.size() > 0)
            leaf_keys(kv.second, key, depth + 1, out);
        else
            out.push_back(key);
    }
}

template <class T>
void read_as(ltm::runtime::Parameters& p, const std::string& key) {
    try {
        p.get<T>(key, T{});
    } catch (const ConfigError& e) {
        ltm::fuzz::expect_one_line(e);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> overrides;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("#set ", 0) == 0) overrides.push_back(line.substr(5));
    const std::string path = ltm::fuzz::write_input(data, size, "launch.yaml");
    ltm::runtime::LaunchConfig cfg;
    try {
        cfg = ltm::runtime::load_launch_config(path, overrides);
    } catch (const ConfigError& e) {
        ltm::fuzz::expect_one_line(e);
        return 0;
    }
    for (const auto& spec : cfg.components) {
        try {
            ltm::runtime::Parameters p(spec.params, cfg.file, spec.name);
            std::vector<std::string> keys;
            leaf_keys(spec.params, "", 0, keys);
            for (std::size_t i = 0; i < keys.size(); ++i) {
                const std::string& key = keys[i];
                p.has(key);
                if (i % 3 == 2) continue;  // some keys stay unread: unknown parameters
                read_as<bool>(p, key);
                read_as<int>(p, key);
                read_as<unsigned>(p, key);
                read_as<std::size_t>(p, key);
                read_as<double>(p, key);
                read_as<std::string>(p, key);
                read_as<std::vector<double>>(p, key);
                read_as<std::vector<std::string>>(p, key);
                try {
                    p.path(key, "", ltm::runtime::PathCheck::kNone);
                } catch (const ConfigError& e) {
                    ltm::fuzz::expect_one_line(e);
                }
            }
            read_as<double>(p, "not.a.key");
            p.check_all_used();
        } catch (const ConfigError& e) {
            ltm::fuzz::expect_one_line(e);
        }
    }
    return 0;
}
