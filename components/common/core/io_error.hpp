#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

#include "common/core/one_line.hpp"

namespace ltm::common {

// A file that cannot be read or written. what() is one line naming the file and the problem
// (control characters quoted from the file are escaped).
class IoError : public std::runtime_error {
  public:
    IoError(const std::string& path, const std::string& problem)
        : std::runtime_error(one_line(path + ": " + problem)), path_(path) {}
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

// Bytes that do not hold what they should (damaged, truncated, from something else).
// what() is one line: "source: field at byte N: problem", or "source: problem" when the problem
// is not about one field. The source is a file, or a record ("Channel record").
class FormatError : public IoError {
  public:
    FormatError(const std::string& source, const std::string& field, std::uint64_t offset,
                const std::string& problem)
        : IoError(source, field + " at byte " + std::to_string(offset) + ": " + problem),
          field_(field),
          problem_(problem),
          offset_(offset) {}
    FormatError(const std::string& source, const std::string& problem)
        : IoError(source, problem), problem_(problem) {}
    const std::string& file() const { return path(); }
    const std::string& field() const { return field_; }  // "" when not about one field
    std::uint64_t offset() const { return offset_; }
    const std::string& problem() const { return problem_; }  // without source, field and offset

  private:
    std::string field_, problem_;
    std::uint64_t offset_ = 0;
};

}  // namespace ltm::common
