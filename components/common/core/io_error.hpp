#pragma once
#include <stdexcept>
#include <string>

namespace ltm::common {

// A file that cannot be read or written. what() is one line naming the file and the problem.
class IoError : public std::runtime_error {
public:
    IoError(const std::string& path, const std::string& problem)
        : std::runtime_error(path + ": " + problem), path_(path) {}
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

}  // namespace ltm::common
