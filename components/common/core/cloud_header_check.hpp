#pragma once
// PCD and PLY headers checked before PCL reads the file. PCL 1.13 crashes, asserts or allocates
// whatever a malformed header claims (each case found by tests/fuzz and kept in its corpus); these
// checks refuse such files with one line instead. Both throw IoError naming the file.
#include <string>

namespace ltm::common {

// Keys PCL needs, counts as plain numbers, known types, no header words after DATA, and the
// bytes PCL will allocate backed by the file.
void check_pcd_header(const std::string& path);

// Keywords and types PCL knows, no list property in the vertex element, and enough bytes after
// the header for every element's fixed-size part.
void check_ply_header(const std::string& path);

}  // namespace ltm::common
