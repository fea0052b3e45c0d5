#pragma once
// MCAP records (https://mcap.dev/spec, major version 0): opcodes, record structs, and their
// little-endian serialisation. Written from the specification; no MCAP library is used.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "MCAP I/O assumes a little-endian host");

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
inline constexpr std::size_t kMessageFixed = 2 + 4 + 8 + 8;

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

// Appends little-endian fields to a byte vector.
class ByteWriter {
  public:
    explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(out) {}
    void u8(std::uint8_t v) { out_.push_back(v); }
    void u16(std::uint16_t v) { raw(&v, 2); }
    void u32(std::uint32_t v) { raw(&v, 4); }
    void u64(std::uint64_t v) { raw(&v, 8); }
    void str(const std::string& s) {
        u32(static_cast<std::uint32_t>(s.size()));
        raw(s.data(), s.size());
    }
    void raw(const void* p, std::size_t n) {
        const auto* b = static_cast<const std::uint8_t*>(p);
        out_.insert(out_.end(), b, b + n);
    }
    // Starts a record; finish it with end_record(start) once its content is written.
    std::size_t begin_record(Op op) {
        const std::size_t start = out_.size();
        u8(static_cast<std::uint8_t>(op));
        u64(0);
        return start;
    }
    void end_record(std::size_t start) {
        const std::uint64_t len = out_.size() - start - kRecordPrefix;
        std::memcpy(out_.data() + start + 1, &len, 8);
    }
    std::size_t size() const { return out_.size(); }

  private:
    std::vector<std::uint8_t>& out_;
};

// Reads little-endian fields from a bounded span; every read checks the bounds and a failed read
// leaves ok() false (and the values zero) instead of reading past the end.
class ByteReader {
  public:
    ByteReader(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
    bool ok() const { return ok_; }
    std::size_t pos() const { return pos_; }
    std::size_t remaining() const { return n_ - pos_; }
    const std::uint8_t* here() const { return p_ + pos_; }
    std::uint8_t u8() { return fixed<std::uint8_t>(); }
    std::uint16_t u16() { return fixed<std::uint16_t>(); }
    std::uint32_t u32() { return fixed<std::uint32_t>(); }
    std::uint64_t u64() { return fixed<std::uint64_t>(); }
    std::string str();
    bool skip(std::uint64_t n);
    // A uint32 byte length followed by that many bytes; returns the span (nullptr on failure).
    const std::uint8_t* span32(std::uint32_t& len);

  private:
    template <typename T>
    T fixed() {
        T v{};
        if (!ok_ || n_ - pos_ < sizeof(T)) {
            ok_ = false;
            return v;
        }
        std::memcpy(&v, p_ + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    const std::uint8_t* p_;
    std::size_t n_;
    std::size_t pos_ = 0;
    bool ok_ = true;
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

// Parsers of a record's content (prefix excluded). Each returns false when the content is too
// short or inconsistent; extra trailing bytes are allowed (fields added by later versions).
bool parse_header(const std::uint8_t* p, std::size_t n, Header& h);
bool parse_schema(const std::uint8_t* p, std::size_t n, Schema& s);
bool parse_channel(const std::uint8_t* p, std::size_t n, Channel& c);
bool parse_message(const std::uint8_t* p, std::size_t n, MessageRecord& m);
bool parse_chunk(const std::uint8_t* p, std::size_t n, ChunkRecord& c);
bool parse_message_index(const std::uint8_t* p, std::size_t n, std::uint16_t& channel_id,
                         std::vector<std::pair<std::uint64_t, std::uint64_t>>& entries);
bool parse_chunk_index(const std::uint8_t* p, std::size_t n, ChunkIndex& c);
bool parse_statistics(const std::uint8_t* p, std::size_t n, Statistics& s);
bool parse_summary_offset(const std::uint8_t* p, std::size_t n, SummaryOffset& s);
bool parse_footer(const std::uint8_t* p, std::size_t n, Footer& f);

}  // namespace ltm::recorder
