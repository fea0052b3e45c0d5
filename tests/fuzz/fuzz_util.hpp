#pragma once
// Shared by the fuzz targets: the input as a file (for readers that take a path) and the check
// that a refusal is what the parser promises (its documented error type, one line).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

namespace ltm::fuzz {

// A folder of this process under /dev/shm (else $TMPDIR or /tmp), created on first use and
// removed at exit.
const std::string& scratch_dir();

// Writes `size` bytes to scratch_dir()/name (replacing it) and returns the path.
std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& name);

// Removes everything inside `dir` (a folder under scratch_dir()), keeping the folder.
void clear_dir(const std::string& dir);

// Aborts (a finding) unless `e`'s message is one non-empty line: every error a user can cause is
// one clear line.
void expect_one_line(const std::exception& e);

// Aborts with `what` (a finding that is not a crash: a broken promise of the parser).
[[noreturn]] void finding(const std::string& what);

}  // namespace ltm::fuzz
