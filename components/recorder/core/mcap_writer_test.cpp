// McapWriter: the bytes it writes are checked against the specification by a raw walk of the
// file that does not use McapReader.
#include "recorder/core/mcap_writer.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <cstring>

#include "common/core/crc32.hpp"
#include "common/core/io_error.hpp"
#include "recorder/core/compression.hpp"
#include "recorder/core/mcap_reader.hpp"
#include "recorder/core/test_util.hpp"

namespace ltm::recorder {
namespace {

struct Rec {
    std::uint8_t op;
    std::uint64_t offset, len;  // len: content length
    const std::uint8_t* content;
};

std::vector<Rec> walk(const std::vector<std::uint8_t>& f, std::size_t from, std::size_t to) {
    std::vector<Rec> out;
    std::size_t pos = from;
    while (pos < to) {
        EXPECT_LE(pos + kRecordPrefix, to);
        std::uint64_t len = 0;
        std::memcpy(&len, f.data() + pos + 1, 8);
        EXPECT_LE(pos + kRecordPrefix + len, to) << "record at " << pos;
        if (pos + kRecordPrefix + len > to) break;
        out.push_back(Rec{f[pos], pos, len, f.data() + pos + kRecordPrefix});
        pos += kRecordPrefix + len;
    }
    return out;
}

// Checks the whole layout of a closed file; returns the number of messages found in chunks.
std::size_t check_layout(const std::vector<std::uint8_t>& f, std::size_t chunk_size,
                         std::size_t max_record) {
    const std::size_t n = f.size();
    EXPECT_EQ(std::memcmp(f.data(), kMcapMagic, 8), 0);
    EXPECT_EQ(std::memcmp(f.data() + n - 8, kMcapMagic, 8), 0);
    const std::size_t footer_at = n - 8 - kFooterRecord;
    EXPECT_EQ(f[footer_at], static_cast<std::uint8_t>(Op::kFooter));
    Footer footer;
    EXPECT_NO_THROW(parse_footer(f.data() + footer_at + kRecordPrefix, kFooterContent, footer));
    EXPECT_EQ(footer.summary_crc,
              common::crc32(f.data() + footer.summary_start,
                            footer_at + kRecordPrefix + 16 - footer.summary_start));
    const std::vector<Rec> data = walk(f, 8, footer.summary_start);
    EXPECT_EQ(data.front().op, static_cast<std::uint8_t>(Op::kHeader));
    Header header;
    EXPECT_NO_THROW(parse_header(data.front().content, data.front().len, header));
    EXPECT_EQ(header.library, "ltm");
    const Rec& data_end = data.back();
    EXPECT_EQ(data_end.op, static_cast<std::uint8_t>(Op::kDataEnd));
    std::uint32_t data_crc = 0;
    std::memcpy(&data_crc, data_end.content, 4);
    EXPECT_EQ(data_crc, common::crc32(f.data(), data_end.offset));

    // Data section: Header, then Chunk followed by its MessageIndex records, then DataEnd.
    std::map<std::uint64_t, std::size_t> chunk_at;  // offset -> position in data
    std::size_t messages = 0;
    for (std::size_t i = 1; i + 1 < data.size(); ++i) {
        const Rec& r = data[i];
        if (r.op == static_cast<std::uint8_t>(Op::kMessageIndex)) {
            EXPECT_TRUE(data[i - 1].op == static_cast<std::uint8_t>(Op::kChunk) ||
                        data[i - 1].op == static_cast<std::uint8_t>(Op::kMessageIndex));
            continue;
        }
        EXPECT_EQ(r.op, static_cast<std::uint8_t>(Op::kChunk)) << "record at " << r.offset;
        chunk_at[r.offset] = i;
        ChunkRecord c;
        EXPECT_NO_THROW(parse_chunk(r.content, r.len, c));
        std::vector<std::uint8_t> records;
        EXPECT_NO_THROW(
            decompress(c.compression, c.records, c.records_size, c.uncompressed_size, records));
        EXPECT_EQ(c.uncompressed_crc, common::crc32(records.data(), records.size()));
        EXPECT_LT(records.size(), chunk_size + max_record);
        // Inside: Schema before the Channel that uses it, Channel before its messages.
        std::set<std::uint16_t> schemas, channels;
        std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> index;
        std::uint64_t lo = ~0ull, hi = 0;
        for (const Rec& in : walk(records, 0, records.size())) {
            if (in.op == static_cast<std::uint8_t>(Op::kSchema)) {
                Schema s;
                EXPECT_NO_THROW(parse_schema(in.content, in.len, s));
                schemas.insert(s.id);
            } else if (in.op == static_cast<std::uint8_t>(Op::kChannel)) {
                Channel ch;
                EXPECT_NO_THROW(parse_channel(in.content, in.len, ch));
                EXPECT_TRUE(ch.schema_id == 0 || schemas.count(ch.schema_id));
                channels.insert(ch.id);
            } else {
                EXPECT_EQ(in.op, static_cast<std::uint8_t>(Op::kMessage));
                MessageRecord m;
                EXPECT_NO_THROW(parse_message(in.content, in.len, m));
                EXPECT_TRUE(channels.count(m.channel_id));
                index[m.channel_id].emplace_back(m.log_time, in.offset);
                lo = std::min(lo, m.log_time);
                hi = std::max(hi, m.log_time);
                ++messages;
            }
        }
        EXPECT_EQ(c.message_start_time, lo);
        EXPECT_EQ(c.message_end_time, hi);
        // The MessageIndex records right after the chunk: one a channel, matching the records.
        std::size_t k = i + 1;
        for (; k < data.size() && data[k].op == static_cast<std::uint8_t>(Op::kMessageIndex); ++k) {
            std::uint16_t ch = 0;
            std::vector<std::pair<std::uint64_t, std::uint64_t>> e;
            EXPECT_NO_THROW(parse_message_index(data[k].content, data[k].len, ch, e));
            auto expect = index[ch];
            std::stable_sort(expect.begin(), expect.end(),
                             [](const auto& a, const auto& b) { return a.first < b.first; });
            EXPECT_EQ(e, expect);
            index.erase(ch);
        }
        EXPECT_TRUE(index.empty());
    }

    // Summary: grouped records, Statistics, ChunkIndexes pointing at the chunks, offsets.
    const std::vector<Rec> summary = walk(f, footer.summary_start, footer.summary_offset_start);
    const std::vector<Rec> offsets = walk(f, footer.summary_offset_start, footer_at);
    std::map<std::uint8_t, std::pair<std::uint64_t, std::uint64_t>> groups;
    for (const Rec& r : summary) {
        auto& g = groups[r.op];
        if (g.second == 0) g.first = r.offset;
        EXPECT_EQ(g.first + g.second, r.offset) << "summary records of one opcode are grouped";
        g.second += kRecordPrefix + r.len;
    }
    EXPECT_EQ(offsets.size(), groups.size());
    for (const Rec& r : offsets) {
        SummaryOffset so;
        EXPECT_NO_THROW(parse_summary_offset(r.content, r.len, so));
        EXPECT_EQ(groups[so.group_opcode], std::make_pair(so.group_start, so.group_length));
    }
    std::size_t chunk_indexes = 0;
    for (const Rec& r : summary) {
        if (r.op == static_cast<std::uint8_t>(Op::kStatistics)) {
            Statistics st;
            EXPECT_NO_THROW(parse_statistics(r.content, r.len, st));
            EXPECT_EQ(st.message_count, messages);
            EXPECT_EQ(st.chunk_count, chunk_at.size());
        }
        if (r.op != static_cast<std::uint8_t>(Op::kChunkIndex)) continue;
        ++chunk_indexes;
        ChunkIndex ci;
        EXPECT_NO_THROW(parse_chunk_index(r.content, r.len, ci));
        EXPECT_TRUE(chunk_at.count(ci.chunk_start_offset));
        const Rec& c = data[chunk_at[ci.chunk_start_offset]];
        EXPECT_EQ(ci.chunk_length, kRecordPrefix + c.len);
        std::uint64_t total = 0;
        for (const auto& [ch, off] : ci.message_index_offsets) {
            EXPECT_EQ(f[off], static_cast<std::uint8_t>(Op::kMessageIndex));
            std::uint16_t got = 0;
            std::memcpy(&got, f.data() + off + kRecordPrefix, 2);
            EXPECT_EQ(got, ch);
            std::uint64_t len = 0;
            std::memcpy(&len, f.data() + off + 1, 8);
            total += kRecordPrefix + len;
        }
        EXPECT_EQ(total, ci.message_index_length);
    }
    EXPECT_EQ(chunk_indexes, chunk_at.size());
    return messages;
}

TEST(McapWriter, LayoutFollowsTheSpecificationForEveryCompression) {
    test::TempDir dir("mcap_writer_layout");
    const auto rec = test::make_recording(500, 3000, 1);
    for (const Compression c : {Compression::kZstd, Compression::kLz4, Compression::kNone}) {
        McapWriterConfig config;
        config.compression = c;
        config.chunk_size = 32 * 1024;
        const std::string path = dir.file(std::string("layout_") + compression_name(c) + ".mcap");
        ASSERT_EQ(test::write_recording(path, rec, config), WriteStatus::kOk);
        const auto bytes = test::read_file(path);
        EXPECT_EQ(check_layout(bytes, config.chunk_size, 3000 + 64), rec.messages.size())
            << compression_name(c);
    }
}

TEST(McapWriter, EmptyRecordingIsAValidFile) {
    test::TempDir dir("mcap_writer_empty");
    {
        McapWriter w(dir.file("empty.mcap"));
        w.add_schema("s", "omgidl", "struct S { long a; };");
        EXPECT_EQ(w.close(), WriteStatus::kOk);
        EXPECT_EQ(w.close(), WriteStatus::kOk);  // idempotent
    }
    EXPECT_EQ(check_layout(test::read_file(dir.file("empty.mcap")), 1, 1), 0u);
    McapReader r(dir.file("empty.mcap"));
    EXPECT_TRUE(r.problem().empty()) << r.problem();
    EXPECT_TRUE(r.verify().ok);
}

TEST(McapWriter, ChunksCloseByLogTimeSpan) {
    test::TempDir dir("mcap_writer_span");
    McapWriterConfig config;
    config.max_chunk_duration = 10000000;  // 10 ms
    McapWriter w(dir.file("span.mcap"), config);
    const auto ch = w.add_channel(0, "t", "json");
    for (std::uint64_t i = 0; i < 100; ++i) {
        ASSERT_EQ(w.write(ch, i * 1000000, i * 1000000, "x", 1), WriteStatus::kOk);
    }
    ASSERT_EQ(w.close(), WriteStatus::kOk);
    McapReader r(dir.file("span.mcap"));
    EXPECT_EQ(r.chunks().size(), 10u);  // 11 messages span 10 ms: 0..10, 11..21, ...
    for (const auto& c : r.chunks()) EXPECT_LE(c.end_time - c.start_time, 10000000u);
}

TEST(McapWriter, RejectsBadUseWithoutCrashing) {
    test::TempDir dir("mcap_writer_bad");
    EXPECT_THROW(McapWriter(dir.file("no/such/folder/x.mcap")), common::IoError);
    McapWriter w(dir.file("bad.mcap"));
    EXPECT_THROW(w.add_channel(7, "t"), std::invalid_argument);
    const auto s = w.add_schema("a", "omgidl", "x");
    EXPECT_THROW(w.add_schema_record(Schema{s, "b", "omgidl", "y"}), std::invalid_argument);
    w.add_schema_record(Schema{s, "a", "omgidl", "x"});  // identical: fine
    EXPECT_EQ(w.write(9, 1, 1, "x", 1), WriteStatus::kUnknownChannel);
    const auto ch = w.add_channel(s, "t");
    EXPECT_EQ(w.write(ch, 1, 1, "x", 1), WriteStatus::kOk);
    EXPECT_EQ(w.close(), WriteStatus::kOk);
    EXPECT_EQ(w.write(ch, 2, 2, "x", 1), WriteStatus::kClosed);
    EXPECT_EQ(w.stats().messages, 1u);
}

TEST(McapWriter, EachClosedChunkIsOnDiskBeforeClose) {
    // What a kill -9 leaves: the file as it is while the writer is still open.
    test::TempDir dir("mcap_writer_open");
    McapWriterConfig config;
    config.chunk_size = 8 * 1024;
    McapWriter w(dir.file("open.mcap"), config);
    const auto ch = w.add_channel(0, "t", "json");
    std::vector<std::uint8_t> payload(1000, 42);
    for (std::uint64_t i = 0; i < 100; ++i) {
        ASSERT_EQ(w.write(ch, i, i, payload.data(), payload.size()), WriteStatus::kOk);
    }
    ASSERT_GT(w.stats().chunks, 5u);
    McapReader r(dir.file("open.mcap"));
    EXPECT_FALSE(r.complete());
    EXPECT_NE(r.problem().find("cut short"), std::string::npos) << r.problem();
    std::size_t n = 0;
    MessageCursor cur = r.messages();
    for (MessageView m; cur.next(m); ++n) EXPECT_EQ(m.log_time, n);
    EXPECT_EQ(n, w.stats().messages);
    EXPECT_LT(n, 100u);
}

TEST(McapWriter, FullDiskStopsCleanlyAndKeepsTheFileValid) {
    // RLIMIT_FSIZE makes write() fail with EFBIG past the limit, as ENOSPC does on a full disk.
    test::TempDir dir("mcap_writer_full");
    const std::string path = dir.file("full.mcap");
    auto rec = test::make_recording(400, 4000, 5);
    McapWriterConfig config;
    config.chunk_size = 16 * 1024;
    config.compression = Compression::kNone;
    rlimit old{};
    ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
    const auto old_handler = signal(SIGXFSZ, SIG_IGN);
    rlimit small = old;
    small.rlim_cur = 200 * 1024;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
    WriteStatus st = WriteStatus::kOk;
    WriterStats stats;
    std::string error;
    std::size_t accepted = 0;
    {
        McapWriter w(path, config);
        for (const auto& s : rec.schemas) w.add_schema(s.name, s.encoding, s.data);
        for (const auto& c : rec.channels)
            w.add_channel(c.schema_id, c.topic, c.message_encoding, c.metadata);
        for (const auto& m : rec.messages) {
            st = w.write(m.channel, m.log_time, m.publish_time, m.data.data(), m.data.size(),
                         m.sequence);
            if (st != WriteStatus::kOk) break;
            ++accepted;
        }
        EXPECT_EQ(w.write(1, 1, 1, "x", 1), WriteStatus::kClosed);
        stats = w.stats();
        error = w.error();
    }
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, old_handler);
    ASSERT_EQ(st, WriteStatus::kDiskFull);
    EXPECT_NE(error.find("disk full"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos);
    EXPECT_EQ(stats.messages + stats.lost_messages, accepted + 1);
    McapReader r(path);
    EXPECT_TRUE(r.complete()) << r.problem();
    const VerifyReport v = r.verify();
    EXPECT_TRUE(v.ok) << (v.problems.empty() ? "" : v.problems.front());
    EXPECT_EQ(v.messages, stats.messages);
    EXPECT_GT(v.messages, 10u);
}

}  // namespace
}  // namespace ltm::recorder
