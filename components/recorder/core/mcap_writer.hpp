#pragma once
// McapWriter: writes an MCAP file (https://mcap.dev/spec) with compressed, indexed chunks.
//
// Layout written: magic, Header, then a sequence of [Chunk, MessageIndex...] where each chunk
// carries the Schema and Channel records of the channels it uses (so each chunk decodes on its
// own), then DataEnd (data section CRC), a summary (Schemas, Channels, Statistics, ChunkIndexes),
// SummaryOffsets, Footer (summary CRC) and magic. Each chunk goes to the file with write() when it
// closes, so a file cut short (kill -9) is readable up to its last complete chunk.
//
// Synchronous and single-threaded: write() compresses and writes when a chunk fills. Producers
// that must never stall use AsyncMcapWriter (recorder/async/), which owns a queue and a thread.
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "recorder/core/compression.hpp"
#include "recorder/core/mcap_records.hpp"

namespace ltm::recorder {

struct McapWriterConfig {
    Compression compression = Compression::kZstd;
    int compression_level = 1;                      // zstd 1..19 / lz4 0 (fast) or 3..12 (HC)
    std::size_t chunk_size = std::size_t{4} << 20;  // bytes of uncompressed records per chunk
    std::uint64_t max_chunk_duration = 1000000000;  // ns of log time one chunk spans; 0: no limit
    bool sync = false;            // fdatasync after each chunk and at close (power-loss safety)
    std::string profile;          // Header profile; "" since schemas are omgidl, not ros2msg/idl
    std::string library = "ltm";  // Header library
};

enum class WriteStatus {
    kOk,
    kDiskFull,        // ENOSPC / EFBIG / EDQUOT: the file was closed cleanly, writing stopped
    kIoError,         // another write error: the file was closed as well as possible
    kClosed,          // the writer was closed or had failed before
    kUnknownChannel,  // no channel with that id was added
};
const char* write_status_name(WriteStatus s);

struct WriterStats {
    std::uint64_t messages = 0;       // messages in chunks written to the file
    std::uint64_t message_bytes = 0;  // their payload bytes
    std::uint64_t chunks = 0;
    std::uint64_t uncompressed_bytes = 0;  // chunk records before compression
    std::uint64_t file_bytes = 0;          // bytes written to the file so far
    std::uint64_t lost_messages = 0;       // messages of a chunk that a write error discarded
};

class McapWriter {
  public:
    // Creates (truncates) `path` and writes magic and Header. Throws common::IoError on failure.
    explicit McapWriter(const std::string& path, McapWriterConfig config = {});
    ~McapWriter();  // close()s if still open; errors are then only visible through error()
    McapWriter(const McapWriter&) = delete;
    McapWriter& operator=(const McapWriter&) = delete;

    // Registers a schema / channel; ids are assigned 1, 2, 3 ... in call order.
    // Throws std::invalid_argument for an unknown schema id or more than 65535 of either.
    std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                             const std::string& data);
    std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                              const std::string& message_encoding = "cdr",
                              const std::map<std::string, std::string>& metadata = {});
    // Registers records keeping their ids (rewriting a file). Re-adding an identical record is a
    // no-op; a different record under a used id throws std::invalid_argument.
    void add_schema_record(const Schema& schema);
    void add_channel_record(const Channel& channel);

    // Appends one message (times in ns). sequence: publisher's counter; the overload without it
    // numbers each channel's messages 1, 2, 3 ... Never throws.
    WriteStatus write(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
                      const void* data, std::size_t size, std::uint32_t sequence);
    WriteStatus write(std::uint16_t channel_id, std::uint64_t log_time, std::uint64_t publish_time,
                      const void* data, std::size_t size);

    // Closes the open chunk now (writes it to the file). No-op without pending messages.
    WriteStatus flush();
    // Writes the last chunk, DataEnd, summary and footer, then closes the file. Idempotent.
    WriteStatus close();

    bool is_open() const { return fd_ >= 0; }
    bool failed() const { return failed_; }
    const std::string& error() const { return error_; }  // one line; empty while all is well
    const WriterStats& stats() const { return stats_; }
    const std::string& path() const { return path_; }
    bool chunk_open() const { return !chunk_.empty(); }
    const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
    const std::map<std::uint16_t, Channel>& channels() const { return channels_; }

  private:
    void start_chunk_channel(std::uint16_t channel_id);
    WriteStatus write_chunk();
    bool write_bytes(const std::uint8_t* p, std::size_t n);
    bool write_tail();
    WriteStatus fail(int err, const std::string& what, std::uint64_t good_pos,
                     std::uint32_t good_crc);

    std::string path_;
    McapWriterConfig config_;
    int fd_ = -1;
    bool failed_ = false;
    std::string error_;
    std::uint64_t pos_ = 0;       // bytes in the file
    std::uint32_t data_crc_ = 0;  // running CRC state of everything before DataEnd
    std::map<std::uint16_t, Schema> schemas_;
    std::map<std::uint16_t, Channel> channels_;
    std::map<std::uint16_t, std::uint32_t> next_sequence_;
    Compressor compressor_;

    // The open chunk.
    std::vector<std::uint8_t> chunk_;
    std::set<std::uint16_t> chunk_schemas_, chunk_channels_;
    std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
    std::uint64_t chunk_start_time_ = 0, chunk_end_time_ = 0;
    std::uint64_t chunk_messages_ = 0, chunk_payload_ = 0;

    std::vector<std::uint8_t> compressed_, scratch_;
    std::vector<ChunkIndex> chunk_indexes_;
    Statistics statistics_;
    WriterStats stats_;
};

}  // namespace ltm::recorder
