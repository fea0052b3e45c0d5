#include "recorder/core/mcap_records.hpp"

#include "common/core/byte_io.hpp"

namespace ltm::recorder {

const char* op_name(std::uint8_t op) {
    switch (static_cast<Op>(op)) {
        case Op::kHeader:
            return "Header";
        case Op::kFooter:
            return "Footer";
        case Op::kSchema:
            return "Schema";
        case Op::kChannel:
            return "Channel";
        case Op::kMessage:
            return "Message";
        case Op::kChunk:
            return "Chunk";
        case Op::kMessageIndex:
            return "MessageIndex";
        case Op::kChunkIndex:
            return "ChunkIndex";
        case Op::kAttachment:
            return "Attachment";
        case Op::kAttachmentIndex:
            return "AttachmentIndex";
        case Op::kStatistics:
            return "Statistics";
        case Op::kMetadata:
            return "Metadata";
        case Op::kMetadataIndex:
            return "MetadataIndex";
        case Op::kSummaryOffset:
            return "SummaryOffset";
        case Op::kDataEnd:
            return "DataEnd";
    }
    return "unknown";
}

namespace {

using Bytes = std::vector<std::uint8_t>;
using common::ByteReader;
using common::ByteWriter;

// Each record's fields are described once: ByteWriter runs the description to write a record,
// ByteReader to parse one (checking bounds; trailing bytes are left for later versions).

// Map<uint16, uint64>: a uint32 byte length, then (key, value) pairs.
template <class IO, class M>
void u16_u64_map(IO& io, M& m, const char* field) {
    if constexpr (IO::kReading) {
        ByteReader e = io.block32(field);
        e.check(e.remaining() % 10 == 0, field, e.offset() - 4, "length is not a multiple of 10");
        m.clear();
        while (e.remaining() > 0) {
            const std::uint16_t k = e.template get<std::uint16_t>(field);
            m[k] = e.template get<std::uint64_t>(field);
        }
    } else {
        const std::size_t at = io.template begin_length<std::uint32_t>();
        for (const auto& [k, v] : m) {
            io.value(k);
            io.value(v);
        }
        io.template end_length<std::uint32_t>(at);
    }
}

// Map<string, string>: a uint32 byte length, then (key, value) pairs.
template <class IO, class M>
void string_map(IO& io, M& m, const char* field) {
    if constexpr (IO::kReading) {
        ByteReader e = io.block32(field);
        m.clear();
        while (e.remaining() > 0) {
            std::string k, v;
            e.str(k, field);
            e.str(v, field);
            m[k] = std::move(v);
        }
    } else {
        const std::size_t at = io.template begin_length<std::uint32_t>();
        for (const auto& [k, v] : m) {
            io.str(k);
            io.str(v);
        }
        io.template end_length<std::uint32_t>(at);
    }
}

// Array<Tuple<uint64, uint64>>: a uint32 byte length, then the pairs.
template <class IO, class E>
void u64_pairs(IO& io, E& entries, const char* field) {
    if constexpr (IO::kReading) {
        ByteReader e = io.block32(field);
        e.check(e.remaining() % 16 == 0, field, e.offset() - 4, "length is not a multiple of 16");
        entries.clear();
        entries.reserve(e.remaining() / 16);
        while (e.remaining() > 0) {
            const std::uint64_t t = e.template get<std::uint64_t>(field);
            entries.emplace_back(t, e.template get<std::uint64_t>(field));
        }
    } else {
        const std::size_t at = io.template begin_length<std::uint32_t>();
        for (const auto& [a, b] : entries) {
            io.value(a);
            io.value(b);
        }
        io.template end_length<std::uint32_t>(at);
    }
}

template <class IO, class H>
void header(IO& io, H& h) {
    io.str(h.profile, "profile");
    io.str(h.library, "library");
}

template <class IO, class S>
void schema(IO& io, S& s) {
    io.value(s.id, "id");
    io.str(s.name, "name");
    io.str(s.encoding, "encoding");
    io.str(s.data, "data");  // uint32 length-prefixed bytes: the layout of a string
}

template <class IO, class C>
void channel(IO& io, C& c) {
    io.value(c.id, "id");
    io.value(c.schema_id, "schema_id");
    io.str(c.topic, "topic");
    io.str(c.message_encoding, "message_encoding");
    string_map(io, c.metadata, "metadata");
}

// The fields before the message data (the rest of the record).
template <class IO, class M>
void message(IO& io, M& m) {
    io.value(m.channel_id, "channel_id");
    io.value(m.sequence, "sequence");
    io.value(m.log_time, "log_time");
    io.value(m.publish_time, "publish_time");
}

// The fields before the records bytes.
template <class IO, class C>
void chunk(IO& io, C& c) {
    io.value(c.message_start_time, "message_start_time");
    io.value(c.message_end_time, "message_end_time");
    io.value(c.uncompressed_size, "uncompressed_size");
    io.value(c.uncompressed_crc, "uncompressed_crc");
    io.str(c.compression, "compression");
    io.value(c.records_size, "records_size");
}

template <class IO, class C>
void chunk_index(IO& io, C& c) {
    io.value(c.message_start_time, "message_start_time");
    io.value(c.message_end_time, "message_end_time");
    io.value(c.chunk_start_offset, "chunk_start_offset");
    io.value(c.chunk_length, "chunk_length");
    u16_u64_map(io, c.message_index_offsets, "message_index_offsets");
    io.value(c.message_index_length, "message_index_length");
    io.str(c.compression, "compression");
    io.value(c.compressed_size, "compressed_size");
    io.value(c.uncompressed_size, "uncompressed_size");
}

template <class IO, class S>
void statistics(IO& io, S& s) {
    io.value(s.message_count, "message_count");
    io.value(s.schema_count, "schema_count");
    io.value(s.channel_count, "channel_count");
    io.value(s.attachment_count, "attachment_count");
    io.value(s.metadata_count, "metadata_count");
    io.value(s.chunk_count, "chunk_count");
    io.value(s.message_start_time, "message_start_time");
    io.value(s.message_end_time, "message_end_time");
    u16_u64_map(io, s.channel_message_counts, "channel_message_counts");
}

template <class IO, class S>
void summary_offset(IO& io, S& s) {
    io.value(s.group_opcode, "group_opcode");
    io.value(s.group_start, "group_start");
    io.value(s.group_length, "group_length");
}

template <class IO, class F>
void footer(IO& io, F& f) {
    io.value(f.summary_start, "summary_start");
    io.value(f.summary_offset_start, "summary_offset_start");
    io.value(f.summary_crc, "summary_crc");
}

// Appends a whole record: opcode, content length (patched in), content. Returns its length.
template <class Content>
std::size_t write_record(Bytes& out, Op op, Content&& content) {
    ByteWriter w(out);
    const std::size_t start = out.size();
    w.value(op);
    const std::size_t at = w.begin_length<std::uint64_t>();
    content(w);
    w.end_length<std::uint64_t>(at);
    return out.size() - start;
}

ByteReader reader(Op op, const std::uint8_t* p, std::size_t n) {
    return ByteReader(std::string(op_name(static_cast<std::uint8_t>(op))) + " record", p, n);
}

}  // namespace

std::size_t write_header(Bytes& out, const Header& h) {
    return write_record(out, Op::kHeader, [&](ByteWriter& w) { header(w, h); });
}

std::size_t write_schema(Bytes& out, const Schema& s) {
    return write_record(out, Op::kSchema, [&](ByteWriter& w) { schema(w, s); });
}

std::size_t write_channel(Bytes& out, const Channel& c) {
    return write_record(out, Op::kChannel, [&](ByteWriter& w) { channel(w, c); });
}

std::size_t write_message(Bytes& out, const MessageRecord& m) {
    return write_record(out, Op::kMessage, [&](ByteWriter& w) {
        message(w, m);
        if (m.size) w.raw(m.data, m.size);
    });
}

std::size_t write_chunk_prefix(Bytes& out, const ChunkRecord& c) {
    // The records follow from the caller: the content length counts them already.
    ByteWriter w(out);
    const std::size_t start = out.size();
    w.value(Op::kChunk);
    w.value<std::uint64_t>(8 + 8 + 8 + 4 + 4 + c.compression.size() + 8 + c.records_size);
    chunk(w, c);
    return out.size() - start;
}

std::size_t write_message_index(Bytes& out, std::uint16_t channel_id,
                                const std::vector<std::pair<std::uint64_t, std::uint64_t>>& e) {
    return write_record(out, Op::kMessageIndex, [&](ByteWriter& w) {
        w.value(channel_id);
        u64_pairs(w, e, "records");
    });
}

std::size_t write_chunk_index(Bytes& out, const ChunkIndex& c) {
    return write_record(out, Op::kChunkIndex, [&](ByteWriter& w) { chunk_index(w, c); });
}

std::size_t write_statistics(Bytes& out, const Statistics& s) {
    return write_record(out, Op::kStatistics, [&](ByteWriter& w) { statistics(w, s); });
}

std::size_t write_summary_offset(Bytes& out, const SummaryOffset& s) {
    return write_record(out, Op::kSummaryOffset, [&](ByteWriter& w) { summary_offset(w, s); });
}

std::size_t write_data_end(Bytes& out, std::uint32_t data_crc) {
    return write_record(out, Op::kDataEnd, [&](ByteWriter& w) { w.value(data_crc); });
}

std::size_t write_footer(Bytes& out, const Footer& f) {
    return write_record(out, Op::kFooter, [&](ByteWriter& w) { footer(w, f); });
}

void parse_header(const std::uint8_t* p, std::size_t n, Header& h) {
    ByteReader r = reader(Op::kHeader, p, n);
    header(r, h);
}

void parse_schema(const std::uint8_t* p, std::size_t n, Schema& s) {
    ByteReader r = reader(Op::kSchema, p, n);
    schema(r, s);
}

void parse_channel(const std::uint8_t* p, std::size_t n, Channel& c) {
    ByteReader r = reader(Op::kChannel, p, n);
    channel(r, c);
}

void parse_message(const std::uint8_t* p, std::size_t n, MessageRecord& m) {
    ByteReader r = reader(Op::kMessage, p, n);
    message(r, m);
    m.size = r.remaining();
    m.data = r.span(m.size, "data");
}

void parse_chunk(const std::uint8_t* p, std::size_t n, ChunkRecord& c) {
    ByteReader r = reader(Op::kChunk, p, n);
    chunk(r, c);
    c.records = r.span(c.records_size, "records");
}

void parse_message_index(const std::uint8_t* p, std::size_t n, std::uint16_t& channel_id,
                         std::vector<std::pair<std::uint64_t, std::uint64_t>>& entries) {
    ByteReader r = reader(Op::kMessageIndex, p, n);
    r.value(channel_id, "channel_id");
    u64_pairs(r, entries, "records");
}

void parse_chunk_index(const std::uint8_t* p, std::size_t n, ChunkIndex& c) {
    ByteReader r = reader(Op::kChunkIndex, p, n);
    chunk_index(r, c);
}

void parse_statistics(const std::uint8_t* p, std::size_t n, Statistics& s) {
    ByteReader r = reader(Op::kStatistics, p, n);
    statistics(r, s);
}

void parse_summary_offset(const std::uint8_t* p, std::size_t n, SummaryOffset& s) {
    ByteReader r = reader(Op::kSummaryOffset, p, n);
    summary_offset(r, s);
}

void parse_footer(const std::uint8_t* p, std::size_t n, Footer& f) {
    ByteReader r = reader(Op::kFooter, p, n);
    footer(r, f);
}

std::string describe(const common::FormatError& e) {
    if (e.field().empty()) return e.problem();
    return e.field() + " at +" + std::to_string(e.offset()) + ": " + e.problem();
}

}  // namespace ltm::recorder
