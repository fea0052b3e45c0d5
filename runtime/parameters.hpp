#pragma once
// A component's parameters: the `params:` map of its launch-config entry. Every read is typed and
// recorded; after construction the host rejects any key nobody read (an unknown parameter).
// Errors name the file, the line and the dotted key.
#include <yaml-cpp/yaml.h>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "runtime/config_error.hpp"

namespace ltm::runtime {

enum class PathCheck { kNone, kFileExists, kDirExists, kParentExists };

class Parameters {
  public:
    // `node` is a map (or null: no parameters); `prefix` names it in messages ("kitti_player").
    Parameters(YAML::Node node, std::string file, std::string prefix);
    // The top-level map of a YAML file (a tool's --config). Throws ConfigError (file:line).
    static Parameters from_file(const std::string& path, const std::string& prefix);

    // Optional value with a default. Dotted keys walk nested maps ("odometry.voxel_size").
    template <class T>
    T get(const std::string& key, const T& fallback);
    // Required value.
    template <class T>
    T require(const std::string& key);
    bool has(const std::string& key) const;

    // A path: ${VAR} and ${VAR:-default} expanded, checked as asked. Empty when absent.
    std::string path(const std::string& key, const std::string& fallback, PathCheck check);

    // Throws ConfigError for `key` (at its line when present).
    [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
    // Throws ConfigError naming the first key that no get/require/path read.
    void check_all_used() const;

    const std::string& file() const { return file_; }
    const std::string& prefix() const { return prefix_; }

  private:
    YAML::Node lookup(const std::string& key) const;
    int line_of(const std::string& key) const;
    std::string full(const std::string& key) const { return prefix_ + "." + key; }
    template <class T>
    T convert(const std::string& key, const YAML::Node& node);

    YAML::Node root_;
    std::string file_, prefix_;
    std::shared_ptr<std::set<std::string>> used_;
};

// Refuses a map key that is not plain text ("? [a, b]: 1"): keys are named by their text.
// Throws ConfigError at the key's line.
void check_plain_keys(const YAML::Node& node, const std::string& file);

// ${VAR} and ${VAR:-default} in a string, from the environment.
std::string expand_env(const std::string& text);

// What a YAML type is called in messages.
template <class T>
const char* yaml_type_name();

}  // namespace ltm::runtime

#include "runtime/parameters_impl.hpp"
