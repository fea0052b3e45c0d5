#pragma once
// Files written and read a piece at a time, for files too large to hold whole in memory (the
// maintained map: ~150 MB on a 1 km site).
//   AtomicFileWriter: appends to PATH.tmp; commit() fsyncs it and renames it over PATH (then
//   fsyncs the folder); destroyed without commit(), it removes PATH.tmp and PATH is untouched.
//   SectionFileReader: the counterpart of ByteWriter::section for a file read in pieces: each
//   section's bytes (length, body, CRC) in a buffer of their own, to read with a ByteReader whose
//   offsets are the file's.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "common/core/byte_io.hpp"

namespace ltm::common {

class AtomicFileWriter {
  public:
    explicit AtomicFileWriter(std::string path);  // throws IoError when PATH.tmp cannot be made
    ~AtomicFileWriter();
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

    void append(const void* bytes, std::size_t size);  // throws IoError
    void append(const std::vector<std::uint8_t>& bytes) { append(bytes.data(), bytes.size()); }
    void commit();  // throws IoError; PATH.tmp is gone either way
    std::uint64_t size() const { return size_; }

  private:
    std::string path_, tmp_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
};

class SectionFileReader {
  public:
    // Throws IoError naming `name_in_errors` when the file cannot be opened.
    SectionFileReader(const std::string& path, std::string name_in_errors);

    // The next n bytes (FormatError naming `field` when the file ends first).
    std::vector<std::uint8_t> bytes(std::size_t n, const char* field);
    // The next section's bytes (uint32 length, body, CRC), unchecked: read them with reader().
    const std::vector<std::uint8_t>& next_section(const char* name);
    // A reader over the last section's bytes, at its offset in the file.
    ByteReader reader() const;
    std::uint64_t offset() const { return offset_; }  // of the next byte in the file
    bool at_end();

  private:
    std::ifstream in_;
    std::string name_;
    std::uint64_t offset_ = 0, section_at_ = 0;
    std::vector<std::uint8_t> section_;
};

}  // namespace ltm::common
