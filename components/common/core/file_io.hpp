#pragma once
// Whole files in and out: reading one into memory, and replacing one atomically.
#include <cstddef>
#include <string>

namespace ltm::common {

// The whole file. Throws IoError naming `name_in_errors` when it cannot be read.
std::string read_file(const std::string& path, const std::string& name_in_errors);

// Writes `bytes` to `path` atomically: PATH.tmp, fsync, rename over PATH, fsync of the folder.
// Throws IoError (naming the path) on failure; a failed write leaves no PATH.tmp behind.
void write_file_atomic(const std::string& path, const void* bytes, std::size_t size);
inline void write_file_atomic(const std::string& path, const std::string& bytes) {
    write_file_atomic(path, bytes.data(), bytes.size());
}

// fsync of a folder (its entries, e.g. after a rename into it): best effort where the folder
// cannot be opened (missing, or a file system that does not open folders); IoError naming the
// folder when the fsync itself fails.
void sync_folder(const std::string& dir);

}  // namespace ltm::common
