#pragma once
// Strict YAML reading for configuration files: every message names the file, the line and the
// dotted key; unknown keys are errors, not silently ignored.
#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <string>
#include <vector>

namespace ltm::sim {

class YamlReader {
  public:
    explicit YamlReader(std::string source) : source_(std::move(source)) {}

    // Throws ScenarioError "SOURCE:LINE: KEY: PROBLEM".
    [[noreturn]] void fail(const YAML::Node& at, const std::string& key,
                           const std::string& problem) const;
    // A map whose keys are all in `allowed`; null counts as an empty map.
    void expect_map(const YAML::Node& node, const std::string& key,
                    std::initializer_list<const char*> allowed) const;
    void expect_sequence(const YAML::Node& node, const std::string& key) const;

    // Reads map[name] into out when present (type-checked); returns whether it was present.
    bool get(const YAML::Node& map, const char* name, const std::string& key, double& out) const;
    bool get(const YAML::Node& map, const char* name, const std::string& key, int& out) const;
    bool get(const YAML::Node& map, const char* name, const std::string& key,
             std::uint64_t& out) const;
    bool get(const YAML::Node& map, const char* name, const std::string& key, bool& out) const;
    bool get(const YAML::Node& map, const char* name, const std::string& key,
             std::string& out) const;
    // A fixed-length list of numbers (length 0: any length).
    bool get_numbers(const YAML::Node& map, const char* name, const std::string& key,
                     std::size_t length, std::vector<double>& out) const;
    // A list of numbers as read from a node.
    std::vector<double> numbers(const YAML::Node& node, const std::string& key, std::size_t min_len,
                                std::size_t max_len) const;

    static std::string join(const std::string& parent, const char* name) {
        return parent.empty() ? std::string(name) : parent + "." + name;
    }
    static std::string index(const std::string& parent, std::size_t i) {
        return parent + "[" + std::to_string(i) + "]";
    }

  private:
    template <typename T>
    bool scalar(const YAML::Node& map, const char* name, const std::string& key, T& out,
                const char* expected) const;
    std::string source_;
};

}  // namespace ltm::sim
