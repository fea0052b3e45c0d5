#pragma once
// Linear reading of MCAP bytes: a pread file source, chunk decoding, record walking, and the
// record-by-record scan of a whole file (used when a file has no usable summary, and by verify).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "recorder/core/mcap_records.hpp"

namespace ltm::recorder {

// A read-only file read with pread. Throws common::IoError when it cannot be opened.
class FileSource {
  public:
    explicit FileSource(const std::string& path);
    ~FileSource();
    FileSource(const FileSource&) = delete;
    FileSource& operator=(const FileSource&) = delete;
    const std::string& path() const { return path_; }
    std::uint64_t size() const { return size_; }
    // Reads exactly n bytes at offset (out is resized); false on a short read or an error.
    bool read(std::uint64_t offset, std::size_t n, std::vector<std::uint8_t>& out) const;

  private:
    std::string path_;
    int fd_ = -1;
    std::uint64_t size_ = 0;
};

// Where a run of messages lives: a Chunk record, or consecutive Message records outside chunks.
struct ChunkInfo {
    std::uint64_t offset = 0;                    // first byte of the record (or run) in the file
    std::uint64_t length = 0;                    // bytes of the record (or run), prefixes included
    std::uint64_t start_time = 0, end_time = 0;  // log-time range of its messages (ns)
    std::string compression;
    std::uint64_t compressed_size = 0, uncompressed_size = 0;
    std::uint64_t messages = 0;   // known after a scan; 0 when read from a chunk index
    bool loose_messages = false;  // true: Message records outside any chunk
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;  // from a chunk index
    std::uint64_t message_index_length = 0;
};

// Decodes one Chunk record's content (prefix excluded) into its uncompressed records, checking
// the CRC when asked and stored. Throws common::FormatError (source "Chunk record").
void decode_chunk(const std::uint8_t* content, std::size_t size, bool check_crc, ChunkRecord& chunk,
                  std::vector<std::uint8_t>& records);

// Calls fn(opcode, content, content_length, record_offset) for each record of a buffer of
// records. Throws common::FormatError (source "records", offset within the buffer) at a record
// that overruns the buffer, after fn has seen the records before it.
void for_each_record(
    const std::uint8_t* p, std::size_t n,
    const std::function<void(std::uint8_t, const std::uint8_t*, std::size_t, std::size_t)>& fn);

struct ScanOptions {
    bool check_crcs = true;              // chunk CRCs and the data-section CRC
    bool check_message_indexes = false;  // compare MessageIndex records with chunk contents
};

struct ScanResult {
    Header header;
    std::map<std::uint16_t, Schema> schemas;
    std::map<std::uint16_t, Channel> channels;
    std::vector<ChunkInfo> chunks;          // intact chunks and loose-message runs, in file order
    Statistics statistics;                  // computed from what was read
    std::vector<std::string> problems;      // one line each, with byte offsets
    std::vector<std::uint64_t> bad_chunks;  // offsets of chunks that failed to decode (skipped)
    std::uint64_t readable_end = 0;         // byte after the last intact data record
    bool data_end_found = false;
    std::uint64_t data_end_offset = 0;
    bool footer_found = false;
};

// Reads every record from the Header on. Stops at the Footer, at DataEnd, or where the file is
// cut or broken (reported in problems). A chunk that fails to decode is skipped and reported.
ScanResult scan_mcap(const FileSource& file, const ScanOptions& options);

// "Chunk", "Message", ... or "opcode 0x42".
std::string describe_op(std::uint8_t op);

}  // namespace ltm::recorder
