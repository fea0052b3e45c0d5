#pragma once
#include <stdexcept>
#include <string>

namespace ltm::runtime {

// A bad launch configuration or parameter. what() is the one line the host prints:
// "FILE:LINE: KEY: PROBLEM".
class ConfigError : public std::runtime_error {
public:
    ConfigError(const std::string& file, int line, const std::string& key, const std::string& problem)
        : std::runtime_error(file + ":" + std::to_string(line) + ": " + key + ": " + problem) {}
};

}  // namespace ltm::runtime
