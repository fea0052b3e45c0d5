#include "recorder/core/mcap_reader.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "common/core/io_error.hpp"
#include "recorder/core/test_util.hpp"

namespace ltm::recorder {
namespace {

using test::TestMessage;

std::vector<TestMessage> read_all(McapReader& r, const ReadOptions& o = {}) {
    std::vector<TestMessage> out;
    MessageCursor cur = r.messages(o);
    for (MessageView m; cur.next(m);) {
        TestMessage t;
        t.channel = m.channel->id;
        t.topic = m.channel->topic;
        t.sequence = m.sequence;
        t.log_time = m.log_time;
        t.publish_time = m.publish_time;
        t.data.assign(m.data, m.data + m.size);
        out.push_back(std::move(t));
    }
    return out;
}

void expect_same(const std::vector<TestMessage>& got, const std::vector<TestMessage>& want) {
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i].channel, want[i].channel) << i;
        EXPECT_EQ(got[i].topic, want[i].topic) << i;
        EXPECT_EQ(got[i].sequence, want[i].sequence) << i;
        EXPECT_EQ(got[i].log_time, want[i].log_time) << i;
        EXPECT_EQ(got[i].publish_time, want[i].publish_time) << i;
        EXPECT_EQ(got[i].data, want[i].data) << i;
    }
}

class McapReaderCompression : public ::testing::TestWithParam<Compression> {};

TEST_P(McapReaderCompression, RoundTripReturnsEveryByteInLogTimeOrder) {
    test::TempDir dir("mcap_reader_rt");
    const auto rec = test::make_recording(700, 5000, 11);
    McapWriterConfig config;
    config.compression = GetParam();
    config.chunk_size = 40 * 1024;
    const std::string path = dir.file("rt.mcap");
    ASSERT_EQ(test::write_recording(path, rec, config), WriteStatus::kOk);
    McapReader r(path);
    EXPECT_TRUE(r.problem().empty()) << r.problem();
    EXPECT_TRUE(r.indexed());
    EXPECT_TRUE(r.complete());
    EXPECT_GT(r.chunks().size(), 10u);
    ASSERT_EQ(r.schemas().size(), 2u);
    ASSERT_EQ(r.channels().size(), 3u);
    for (const auto& s : rec.schemas) EXPECT_EQ(r.schemas().at(s.id), s);
    for (const auto& c : rec.channels) EXPECT_EQ(r.channels().at(c.id), c);
    EXPECT_EQ(r.statistics().message_count, rec.messages.size());
    expect_same(read_all(r), test::by_log_time(rec.messages));
    // Schemas reach the messages.
    MessageCursor cur = r.messages({{"rt/pose"}});
    MessageView m;
    ASSERT_TRUE(cur.next(m));
    ASSERT_NE(m.schema, nullptr);
    EXPECT_EQ(m.schema->name, "test::msg::dds_::Pose_");
    const VerifyReport v = r.verify();
    EXPECT_TRUE(v.ok) << (v.problems.empty() ? "" : v.problems.front());
}

INSTANTIATE_TEST_SUITE_P(All, McapReaderCompression,
                         ::testing::Values(Compression::kZstd, Compression::kLz4,
                                           Compression::kNone));

TEST(McapReader, TimeWindowSeeksWithTheChunkIndexAndTopicsFilter) {
    test::TempDir dir("mcap_reader_seek");
    const auto rec = test::make_recording(1000, 2000, 12);
    McapWriterConfig config;
    config.chunk_size = 16 * 1024;
    const std::string path = dir.file("seek.mcap");
    ASSERT_EQ(test::write_recording(path, rec, config), WriteStatus::kOk);
    McapReader r(path);
    ASSERT_TRUE(r.indexed());
    ReadOptions o;
    o.start_time = 1000000000ull + 400 * 1000000ull;
    o.end_time = 1000000000ull + 450 * 1000000ull;
    o.topics = {"rt/points", "rt/log"};
    std::vector<TestMessage> want;
    for (const auto& m : test::by_log_time(rec.messages)) {
        if (m.log_time >= o.start_time && m.log_time <= o.end_time && m.topic != "rt/pose") {
            want.push_back(m);
        }
    }
    ASSERT_GT(want.size(), 10u);
    MessageCursor cur = r.messages(o);
    std::vector<TestMessage> got;
    for (MessageView m; cur.next(m);) {
        got.push_back(TestMessage{m.channel->id, m.channel->topic, m.sequence, m.log_time,
                                  m.publish_time,
                                  std::vector<std::uint8_t>(m.data, m.data + m.size)});
    }
    expect_same(got, want);
    EXPECT_LT(cur.chunks_loaded(), r.chunks().size() / 4);  // only the chunks of the window
    EXPECT_GE(cur.chunks_loaded(), 1u);
    EXPECT_TRUE(read_all(r, ReadOptions{{"rt/none"}, 0, ~0ull, true}).empty());
}

// Offsets of the chunk records of a complete file, in file order, with their message counts.
std::vector<std::pair<std::uint64_t, std::uint64_t>> chunk_ends(const std::string& path) {
    McapReader r(path);
    std::vector<std::pair<std::uint64_t, std::uint64_t>> out;
    for (const auto& c : r.chunks()) out.emplace_back(c.offset + c.length, 0);
    // Messages a chunk holds: read each chunk's window alone is not exact with overlaps, so
    // count through a scan instead.
    const ScanResult s = scan_mcap(r.file(), ScanOptions{});
    for (std::size_t i = 0; i < s.chunks.size(); ++i) out[i].second = s.chunks[i].messages;
    return out;
}

TEST(McapReader, CutFilesAreReadableUpToTheirLastCompleteChunk) {
    test::TempDir dir("mcap_reader_cut");
    const auto rec = test::make_recording(300, 3000, 13);
    McapWriterConfig config;
    config.chunk_size = 20 * 1024;
    const std::string path = dir.file("full.mcap");
    ASSERT_EQ(test::write_recording(path, rec, config), WriteStatus::kOk);
    const auto bytes = test::read_file(path);
    const auto ends = chunk_ends(path);
    ASSERT_GT(ends.size(), 5u);
    std::vector<std::size_t> cuts = {8, 9, 20, 30};
    for (std::size_t c = 40; c < bytes.size(); c += bytes.size() / 37) cuts.push_back(c);
    for (const auto& e : ends) {
        cuts.push_back(e.first - 1);
        cuts.push_back(e.first);
        cuts.push_back(e.first + 5);
    }
    cuts.push_back(bytes.size() - 1);
    const auto sorted = test::by_log_time(rec.messages);
    for (const std::size_t cut : cuts) {
        const std::string p = dir.file("cut.mcap");
        test::write_file(p, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + cut));
        McapReader r(p);
        EXPECT_FALSE(r.problem().empty()) << cut;
        EXPECT_EQ(r.problem().find('\n'), std::string::npos);
        std::uint64_t expected = 0;
        for (const auto& e : ends) {
            if (e.first <= cut) expected += e.second;
        }
        const auto got = read_all(r);
        EXPECT_EQ(got.size(), expected) << "cut at " << cut << ": " << r.problem();
        // What is read is exactly the messages written first, in log-time order.
        for (std::size_t i = 1; i < got.size(); ++i)
            EXPECT_LE(got[i - 1].log_time, got[i].log_time);
        std::size_t matched = 0;
        for (const auto& g : got) {
            for (const auto& w : sorted) {
                if (w.log_time == g.log_time && w.channel == g.channel && w.data == g.data) {
                    ++matched;
                    break;
                }
            }
        }
        EXPECT_EQ(matched, got.size());
    }
}

TEST(McapReader, CorruptedChunkIsReportedWithItsOffsetAndSkipped) {
    test::TempDir dir("mcap_reader_crc");
    const auto rec = test::make_recording(300, 3000, 14);
    for (const Compression comp : {Compression::kNone, Compression::kZstd}) {
        McapWriterConfig config;
        config.chunk_size = 20 * 1024;
        config.compression = comp;
        const std::string path = dir.file("crc.mcap");
        ASSERT_EQ(test::write_recording(path, rec, config), WriteStatus::kOk);
        auto bytes = test::read_file(path);
        std::uint64_t bad_at = 0, bad_messages = 0;
        {
            McapReader r(path);
            const ChunkInfo c = r.chunks()[3];
            bad_at = c.offset;
            bad_messages = scan_mcap(r.file(), ScanOptions{}).chunks[3].messages;
            bytes[c.offset + c.length - 100] ^= 0x5A;  // inside the records
        }
        test::write_file(path, bytes);
        McapReader r(path);
        EXPECT_TRUE(r.indexed());  // the summary is intact
        const auto got = read_all(r);
        EXPECT_EQ(got.size(), rec.messages.size() - bad_messages);
        ASSERT_FALSE(r.problem().empty());
        EXPECT_NE(r.problem().find("Chunk at byte " + std::to_string(bad_at)), std::string::npos)
            << r.problem();
        if (comp == Compression::kNone) {
            EXPECT_NE(r.problem().find("CRC mismatch"), std::string::npos) << r.problem();
        }
        // verify() names the chunk and the data-section CRC, nothing that follows from them.
        const VerifyReport v = r.verify();
        EXPECT_FALSE(v.ok);
        ASSERT_EQ(v.problems.size(), 2u) << v.problems.back();
        EXPECT_NE(v.problems[0].find("Chunk at byte " + std::to_string(bad_at)), std::string::npos);
        EXPECT_NE(v.problems[1].find("data section CRC mismatch"), std::string::npos);
    }
}

TEST(McapReader, DamagedSummaryFallsBackToLinearScan) {
    test::TempDir dir("mcap_reader_summary");
    const auto rec = test::make_recording(200, 1000, 15);
    const std::string path = dir.file("sum.mcap");
    ASSERT_EQ(test::write_recording(path, rec, McapWriterConfig{}), WriteStatus::kOk);
    auto bytes = test::read_file(path);
    bytes[bytes.size() - 8 - kFooterRecord - 20] ^= 0x01;  // a summary offset record
    test::write_file(path, bytes);
    McapReader r(path);
    EXPECT_FALSE(r.indexed());
    EXPECT_NE(r.problem().find("summary CRC mismatch"), std::string::npos) << r.problem();
    expect_same(read_all(r), test::by_log_time(rec.messages));
}

TEST(McapReader, NonMcapInputIsRejectedInOneLine) {
    test::TempDir dir("mcap_reader_bad");
    const std::vector<std::pair<std::string, std::vector<std::uint8_t>>> cases = {
        {"empty", {}},
        {"short", {0x89, 'M', 'C'}},
        {"text", std::vector<std::uint8_t>(100, 'a')},
        {"version", {0x89, 'M', 'C', 'A', 'P', '1', '\r', '\n', 1, 0, 0, 0, 0, 0, 0, 0, 0}},
        {"no_header", {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n', 5, 0, 0, 0, 0, 0, 0, 0, 0}},
    };
    for (const auto& [name, bytes] : cases) {
        const std::string p = dir.file(name);
        test::write_file(p, bytes);
        try {
            McapReader r(p);
            ADD_FAILURE() << name << " was accepted";
        } catch (const common::IoError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            EXPECT_NE(what.find(p), std::string::npos) << what;
            EXPECT_TRUE(what.find("not an MCAP file") != std::string::npos ||
                        what.find("version") != std::string::npos)
                << what;
        }
    }
    EXPECT_THROW(McapReader(dir.file("missing.mcap")), common::IoError);
    EXPECT_THROW(McapReader(dir.file("")), common::IoError);  // a folder
}

TEST(McapReader, ReadsMessagesOutsideChunks) {
    // An unchunked file, as other writers may produce: Header, Schema, Channel, Messages, DataEnd,
    // Footer without summary.
    test::TempDir dir("mcap_reader_loose");
    std::vector<std::uint8_t> f(kMcapMagic, kMcapMagic + 8);
    write_header(f, Header{"", "hand"});
    write_schema(f, Schema{1, "S", "omgidl", "struct S { long a; };"});
    write_channel(f, Channel{0, 1, "loose", "cdr", {}});
    const std::uint8_t payload[3] = {1, 2, 3};
    for (std::uint64_t t : {30, 10, 20}) write_message(f, MessageRecord{0, 0, t, t, payload, 3});
    write_data_end(f, 0);
    write_footer(f, Footer{});
    f.insert(f.end(), kMcapMagic, kMcapMagic + 8);
    test::write_file(dir.file("loose.mcap"), f);
    McapReader r(dir.file("loose.mcap"));
    EXPECT_TRUE(r.problem().empty()) << r.problem();
    EXPECT_TRUE(r.complete());
    EXPECT_FALSE(r.indexed());
    const auto got = read_all(r);
    ASSERT_EQ(got.size(), 3u);
    EXPECT_EQ(got[0].log_time, 10u);
    EXPECT_EQ(got[2].log_time, 30u);
    EXPECT_EQ(got[1].topic, "loose");
    EXPECT_EQ(r.statistics().message_count, 3u);
}

}  // namespace
}  // namespace ltm::recorder
