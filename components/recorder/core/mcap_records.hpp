#pragma once
// MCAP records (https://mcap.dev/spec, major version 0): opcodes, record structs, and their
// little-endian serialisation (common/core/byte_io.hpp: each record's layout is described once,
// for writing and parsing). Written from the specification; no MCAP library is used.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/core/io_error.hpp"

namespace ltm::recorder {

// "\x89MCAP0\r\n": first and last 8 bytes of every MCAP file.
inline constexpr std::uint8_t kMcapMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr std::size_t kMagicSize = 8;
inline constexpr std::size_t kRecordPrefix = 9;  // opcode (1) + content length (8)
inline constexpr std::size_t kFooterContent = 20;
inline constexpr std::size_t kFooterRecord = kRecordPrefix + kFooterContent;
inline constexpr std::size_t kDataEndRecord = kRecordPrefix + 4;

enum class Op : std::uint8_t {
    kHeader = 0x01,
    kFooter = 0x02,
    kSchema = 0x03,
    kChannel = 0x04,
    kMessage = 0x05,
    kChunk = 0x06,
    kMessageIndex = 0x07,
    kChunkIndex = 0x08,
    kAttachment = 0x09,
    kAttachmentIndex = 0x0A,
    kStatistics = 0x0B,
    kMetadata = 0x0C,
    kMetadataIndex = 0x0D,
    kSummaryOffset = 0x0E,
    kDataEnd = 0x0F,
};
const char* op_name(std::uint8_t op);

struct Header {
    std::string profile;
    std::string library;
};

struct Schema {
    std::uint16_t id = 0;  // never 0 in a file
    std::string name;      // e.g. "sensor_msgs::msg::dds_::PointCloud2_"
    std::string encoding;  // e.g. "omgidl"
    std::string data;      // schema text (bytes)
    bool operator==(const Schema& o) const {
        return id == o.id && name == o.name && encoding == o.encoding && data == o.data;
    }
};

struct Channel {
    std::uint16_t id = 0;
    std::uint16_t schema_id = 0;  // 0: no schema
    std::string topic;
    std::string message_encoding;  // e.g. "cdr"
    std::map<std::string, std::string> metadata;
    bool operator==(const Channel& o) const {
        return id == o.id && schema_id == o.schema_id && topic == o.topic &&
               message_encoding == o.message_encoding && metadata == o.metadata;
    }
};

// A Message record's fields; data points into a buffer owned elsewhere.
struct MessageRecord {
    std::uint16_t channel_id = 0;
    std::uint32_t sequence = 0;
    std::uint64_t log_time = 0;      // ns
    std::uint64_t publish_time = 0;  // ns
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
};

// A Chunk record's fields; records points into the record's bytes (compressed).
struct ChunkRecord {
    std::uint64_t message_start_time = 0;
    std::uint64_t message_end_time = 0;
    std::uint64_t uncompressed_size = 0;
    std::uint32_t uncompressed_crc = 0;  // 0: not set
    std::string compression;             // "", "zstd", "lz4"
    const std::uint8_t* records = nullptr;
    std::uint64_t records_size = 0;
};

struct ChunkIndex {
    std::uint64_t message_start_time = 0;
    std::uint64_t message_end_time = 0;
    std::uint64_t chunk_start_offset = 0;
    std::uint64_t chunk_length = 0;  // whole record, opcode and length included
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length = 0;
    std::string compression;
    std::uint64_t compressed_size = 0;
    std::uint64_t uncompressed_size = 0;
};

struct Statistics {
    std::uint64_t message_count = 0;
    std::uint16_t schema_count = 0;
    std::uint32_t channel_count = 0;
    std::uint32_t attachment_count = 0;
    std::uint32_t metadata_count = 0;
    std::uint32_t chunk_count = 0;
    std::uint64_t message_start_time = 0;
    std::uint64_t message_end_time = 0;
    std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

struct SummaryOffset {
    std::uint8_t group_opcode = 0;
    std::uint64_t group_start = 0;
    std::uint64_t group_length = 0;
};

struct Footer {
    std::uint64_t summary_start = 0;         // 0: no summary
    std::uint64_t summary_offset_start = 0;  // 0: no summary offsets
    std::uint32_t summary_crc = 0;           // 0: not available
};

// Serialisers: append one whole record (prefix included) and return its length in bytes.
std::size_t write_header(std::vector<std::uint8_t>& out, const Header& h);
std::size_t write_schema(std::vector<std::uint8_t>& out, const Schema& s);
std::size_t write_channel(std::vector<std::uint8_t>& out, const Channel& c);
std::size_t write_message(std::vector<std::uint8_t>& out, const MessageRecord& m);
// Chunk record prefix and fields up to and including the records length; the caller appends the
// (compressed) records bytes. Returns the number of bytes appended.
std::size_t write_chunk_prefix(std::vector<std::uint8_t>& out, const ChunkRecord& c);
std::size_t write_message_index(std::vector<std::uint8_t>& out, std::uint16_t channel_id,
                                const std::vector<std::pair<std::uint64_t, std::uint64_t>>& e);
std::size_t write_chunk_index(std::vector<std::uint8_t>& out, const ChunkIndex& c);
std::size_t write_statistics(std::vector<std::uint8_t>& out, const Statistics& s);
std::size_t write_summary_offset(std::vector<std::uint8_t>& out, const SummaryOffset& s);
std::size_t write_data_end(std::vector<std::uint8_t>& out, std::uint32_t data_crc);
// Footer record (prefix included); the summary CRC covers the footer up to summary_crc.
std::size_t write_footer(std::vector<std::uint8_t>& out, const Footer& f);

// Parsers of a record's content (prefix excluded). Each throws common::FormatError when the
// content is too short or inconsistent (source "Channel record", offsets within the content);
// extra trailing bytes are allowed (fields added by later versions).
void parse_header(const std::uint8_t* p, std::size_t n, Header& h);
void parse_schema(const std::uint8_t* p, std::size_t n, Schema& s);
void parse_channel(const std::uint8_t* p, std::size_t n, Channel& c);
void parse_message(const std::uint8_t* p, std::size_t n, MessageRecord& m);
void parse_chunk(const std::uint8_t* p, std::size_t n, ChunkRecord& c);
void parse_message_index(const std::uint8_t* p, std::size_t n, std::uint16_t& channel_id,
                         std::vector<std::pair<std::uint64_t, std::uint64_t>>& entries);
void parse_chunk_index(const std::uint8_t* p, std::size_t n, ChunkIndex& c);
void parse_statistics(const std::uint8_t* p, std::size_t n, Statistics& s);
void parse_summary_offset(const std::uint8_t* p, std::size_t n, SummaryOffset& s);
void parse_footer(const std::uint8_t* p, std::size_t n, Footer& f);

// An error of a record's content for a problem line: "topic at +12: truncated: needs 9 bytes,
// 3 left".
std::string describe(const common::FormatError& e);

}  // namespace ltm::recorder
