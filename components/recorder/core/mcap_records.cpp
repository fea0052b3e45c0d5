#include "recorder/core/mcap_records.hpp"

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

std::string ByteReader::str() {
    std::uint32_t len = 0;
    const std::uint8_t* s = span32(len);
    return s ? std::string(reinterpret_cast<const char*>(s), len) : std::string();
}

bool ByteReader::skip(std::uint64_t n) {
    if (!ok_ || remaining() < n) return ok_ = false;
    pos_ += static_cast<std::size_t>(n);
    return true;
}

const std::uint8_t* ByteReader::span32(std::uint32_t& len) {
    len = u32();
    const std::uint8_t* s = here();
    if (!skip(len)) {
        len = 0;
        return nullptr;
    }
    return s;
}

namespace {

using Bytes = std::vector<std::uint8_t>;

// Map<uint16, uint64>: a uint32 byte length, then (key, value) pairs.
void put_u16_u64_map(ByteWriter& w, const std::map<std::uint16_t, std::uint64_t>& m) {
    w.u32(static_cast<std::uint32_t>(m.size() * 10));
    for (const auto& [k, v] : m) {
        w.u16(k);
        w.u64(v);
    }
}

bool get_u16_u64_map(ByteReader& r, std::map<std::uint16_t, std::uint64_t>& m) {
    std::uint32_t len = 0;
    const std::uint8_t* p = r.span32(len);
    if (!p || len % 10 != 0) return false;
    ByteReader e(p, len);
    while (e.remaining() > 0) {
        const std::uint16_t k = e.u16();
        m[k] = e.u64();
    }
    return e.ok();
}

std::size_t finish(ByteWriter& w, std::size_t start) {
    w.end_record(start);
    return w.size() - start;
}

}  // namespace

std::size_t write_header(Bytes& out, const Header& h) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kHeader);
    w.str(h.profile);
    w.str(h.library);
    return finish(w, s);
}

std::size_t write_schema(Bytes& out, const Schema& sc) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kSchema);
    w.u16(sc.id);
    w.str(sc.name);
    w.str(sc.encoding);
    w.str(sc.data);  // uint32 length-prefixed bytes: same layout as a string
    return finish(w, s);
}

std::size_t write_channel(Bytes& out, const Channel& c) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kChannel);
    w.u16(c.id);
    w.u16(c.schema_id);
    w.str(c.topic);
    w.str(c.message_encoding);
    std::uint32_t map_len = 0;
    for (const auto& [k, v] : c.metadata)
        map_len += static_cast<std::uint32_t>(8 + k.size() + v.size());
    w.u32(map_len);
    for (const auto& [k, v] : c.metadata) {
        w.str(k);
        w.str(v);
    }
    return finish(w, s);
}

std::size_t write_message(Bytes& out, const MessageRecord& m) {
    ByteWriter w(out);
    w.u8(static_cast<std::uint8_t>(Op::kMessage));
    w.u64(kMessageFixed + m.size);
    w.u16(m.channel_id);
    w.u32(m.sequence);
    w.u64(m.log_time);
    w.u64(m.publish_time);
    if (m.size) w.raw(m.data, m.size);
    return kRecordPrefix + kMessageFixed + m.size;
}

std::size_t write_chunk_prefix(Bytes& out, const ChunkRecord& c) {
    ByteWriter w(out);
    const std::size_t start = w.size();
    const std::uint64_t content = 8 + 8 + 8 + 4 + 4 + c.compression.size() + 8 + c.records_size;
    w.u8(static_cast<std::uint8_t>(Op::kChunk));
    w.u64(content);
    w.u64(c.message_start_time);
    w.u64(c.message_end_time);
    w.u64(c.uncompressed_size);
    w.u32(c.uncompressed_crc);
    w.str(c.compression);
    w.u64(c.records_size);
    return w.size() - start;
}

std::size_t write_message_index(Bytes& out, std::uint16_t channel_id,
                                const std::vector<std::pair<std::uint64_t, std::uint64_t>>& e) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kMessageIndex);
    w.u16(channel_id);
    w.u32(static_cast<std::uint32_t>(e.size() * 16));
    for (const auto& [time, offset] : e) {
        w.u64(time);
        w.u64(offset);
    }
    return finish(w, s);
}

std::size_t write_chunk_index(Bytes& out, const ChunkIndex& c) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kChunkIndex);
    w.u64(c.message_start_time);
    w.u64(c.message_end_time);
    w.u64(c.chunk_start_offset);
    w.u64(c.chunk_length);
    put_u16_u64_map(w, c.message_index_offsets);
    w.u64(c.message_index_length);
    w.str(c.compression);
    w.u64(c.compressed_size);
    w.u64(c.uncompressed_size);
    return finish(w, s);
}

std::size_t write_statistics(Bytes& out, const Statistics& st) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kStatistics);
    w.u64(st.message_count);
    w.u16(st.schema_count);
    w.u32(st.channel_count);
    w.u32(st.attachment_count);
    w.u32(st.metadata_count);
    w.u32(st.chunk_count);
    w.u64(st.message_start_time);
    w.u64(st.message_end_time);
    put_u16_u64_map(w, st.channel_message_counts);
    return finish(w, s);
}

std::size_t write_summary_offset(Bytes& out, const SummaryOffset& so) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kSummaryOffset);
    w.u8(so.group_opcode);
    w.u64(so.group_start);
    w.u64(so.group_length);
    return finish(w, s);
}

std::size_t write_data_end(Bytes& out, std::uint32_t data_crc) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kDataEnd);
    w.u32(data_crc);
    return finish(w, s);
}

std::size_t write_footer(Bytes& out, const Footer& f) {
    ByteWriter w(out);
    const std::size_t s = w.begin_record(Op::kFooter);
    w.u64(f.summary_start);
    w.u64(f.summary_offset_start);
    w.u32(f.summary_crc);
    return finish(w, s);
}

bool parse_header(const std::uint8_t* p, std::size_t n, Header& h) {
    ByteReader r(p, n);
    h.profile = r.str();
    h.library = r.str();
    return r.ok();
}

bool parse_schema(const std::uint8_t* p, std::size_t n, Schema& s) {
    ByteReader r(p, n);
    s.id = r.u16();
    s.name = r.str();
    s.encoding = r.str();
    s.data = r.str();
    return r.ok();
}

bool parse_channel(const std::uint8_t* p, std::size_t n, Channel& c) {
    ByteReader r(p, n);
    c.id = r.u16();
    c.schema_id = r.u16();
    c.topic = r.str();
    c.message_encoding = r.str();
    std::uint32_t len = 0;
    const std::uint8_t* m = r.span32(len);
    if (!r.ok() || !m) return false;
    ByteReader e(m, len);
    c.metadata.clear();
    while (e.ok() && e.remaining() > 0) {
        std::string k = e.str();
        c.metadata[k] = e.str();
    }
    return e.ok();
}

bool parse_message(const std::uint8_t* p, std::size_t n, MessageRecord& m) {
    if (n < kMessageFixed) return false;
    ByteReader r(p, n);
    m.channel_id = r.u16();
    m.sequence = r.u32();
    m.log_time = r.u64();
    m.publish_time = r.u64();
    m.data = r.here();
    m.size = r.remaining();
    return r.ok();
}

bool parse_chunk(const std::uint8_t* p, std::size_t n, ChunkRecord& c) {
    ByteReader r(p, n);
    c.message_start_time = r.u64();
    c.message_end_time = r.u64();
    c.uncompressed_size = r.u64();
    c.uncompressed_crc = r.u32();
    c.compression = r.str();
    c.records_size = r.u64();
    c.records = r.here();
    return r.ok() && r.skip(c.records_size);
}

bool parse_message_index(const std::uint8_t* p, std::size_t n, std::uint16_t& channel_id,
                         std::vector<std::pair<std::uint64_t, std::uint64_t>>& entries) {
    ByteReader r(p, n);
    channel_id = r.u16();
    std::uint32_t len = 0;
    const std::uint8_t* a = r.span32(len);
    if (!r.ok() || !a || len % 16 != 0) return false;
    ByteReader e(a, len);
    entries.clear();
    entries.reserve(len / 16);
    while (e.remaining() > 0) {
        const std::uint64_t t = e.u64();
        entries.emplace_back(t, e.u64());
    }
    return e.ok();
}

bool parse_chunk_index(const std::uint8_t* p, std::size_t n, ChunkIndex& c) {
    ByteReader r(p, n);
    c.message_start_time = r.u64();
    c.message_end_time = r.u64();
    c.chunk_start_offset = r.u64();
    c.chunk_length = r.u64();
    c.message_index_offsets.clear();
    if (!r.ok() || !get_u16_u64_map(r, c.message_index_offsets)) return false;
    c.message_index_length = r.u64();
    c.compression = r.str();
    c.compressed_size = r.u64();
    c.uncompressed_size = r.u64();
    return r.ok();
}

bool parse_statistics(const std::uint8_t* p, std::size_t n, Statistics& s) {
    ByteReader r(p, n);
    s.message_count = r.u64();
    s.schema_count = r.u16();
    s.channel_count = r.u32();
    s.attachment_count = r.u32();
    s.metadata_count = r.u32();
    s.chunk_count = r.u32();
    s.message_start_time = r.u64();
    s.message_end_time = r.u64();
    s.channel_message_counts.clear();
    return r.ok() && get_u16_u64_map(r, s.channel_message_counts);
}

bool parse_summary_offset(const std::uint8_t* p, std::size_t n, SummaryOffset& s) {
    ByteReader r(p, n);
    s.group_opcode = r.u8();
    s.group_start = r.u64();
    s.group_length = r.u64();
    return r.ok();
}

bool parse_footer(const std::uint8_t* p, std::size_t n, Footer& f) {
    ByteReader r(p, n);
    f.summary_start = r.u64();
    f.summary_offset_start = r.u64();
    f.summary_crc = r.u32();
    return r.ok();
}

}  // namespace ltm::recorder
