// The MCAP records of the byte reader/writer: testdata/records_v0.bin was written by the record
// serialisers of commit 9b8af10 (before they moved to common/core/byte_io) from
// write_sample_records() below; today's serialisers must give the same bytes, and the parsers
// must read them back.
#include "recorder/core/mcap_records.hpp"

#include <gtest/gtest.h>

#include <map>

#include "recorder/core/mcap_scan.hpp"
#include "recorder/core/test_util.hpp"

namespace ltm::recorder {
namespace {

const std::string kFixture =
    std::string(LTM_SOURCE_DIR) + "/components/recorder/core/testdata/records_v0.bin";

// Every record type once, with fields that are not zero. Appends them to `out`.
void write_sample_records(std::vector<std::uint8_t>& out) {
    write_header(out, Header{"ros2", "ltm test"});
    Schema s;
    s.id = 3;
    s.name = "sensor_msgs::msg::dds_::PointCloud2_";
    s.encoding = "omgidl";
    s.data = std::string("module a { struct B { long c; }; };\0x", 38);
    write_schema(out, s);
    Channel c;
    c.id = 7;
    c.schema_id = 3;
    c.topic = "rt/robot/points";
    c.message_encoding = "cdr";
    c.metadata = {{"offered_qos_profiles", "- history: 1"}, {"z", ""}};
    write_channel(out, c);
    const std::uint8_t payload[5] = {0, 1, 2, 0xfe, 0xff};
    MessageRecord m;
    m.channel_id = 7;
    m.sequence = 42;
    m.log_time = 1'700'000'000'123'456'789ull;
    m.publish_time = 1'700'000'000'123'000'000ull;
    m.data = payload;
    m.size = sizeof(payload);
    std::vector<std::uint8_t> records;
    write_message(records, m);
    ChunkRecord k;
    k.message_start_time = m.log_time;
    k.message_end_time = m.log_time + 5;
    k.uncompressed_size = records.size();
    k.uncompressed_crc = 0x12345678u;
    k.compression = "";
    k.records_size = records.size();
    write_chunk_prefix(out, k);
    out.insert(out.end(), records.begin(), records.end());
    write_message_index(out, 7, {{m.log_time, 0}, {m.log_time + 5, 39}});
    write_data_end(out, 0xdeadbeefu);
    ChunkIndex ci;
    ci.message_start_time = 11;
    ci.message_end_time = 12;
    ci.chunk_start_offset = 400;
    ci.chunk_length = 90;
    ci.message_index_offsets = {{7, 500}, {9, 531}};
    ci.message_index_length = 62;
    ci.compression = "zstd";
    ci.compressed_size = 55;
    ci.uncompressed_size = 66;
    write_chunk_index(out, ci);
    Statistics st;
    st.message_count = 2;
    st.schema_count = 1;
    st.channel_count = 1;
    st.attachment_count = 4;
    st.metadata_count = 5;
    st.chunk_count = 1;
    st.message_start_time = 11;
    st.message_end_time = 12;
    st.channel_message_counts = {{7, 2}};
    write_statistics(out, st);
    write_summary_offset(out, SummaryOffset{0x08, 600, 70});
    write_footer(out, Footer{600, 700, 0xcafef00du});
}

TEST(McapRecords, WritersGiveTheBytesOfTheOldSerialisers) {
    std::vector<std::uint8_t> out;
    write_sample_records(out);
    EXPECT_TRUE(out == test::read_file(kFixture)) << out.size() << " bytes";
}

TEST(McapRecords, ParsersReadEveryRecordBack) {
    const std::vector<std::uint8_t> bytes = test::read_file(kFixture);
    std::map<Op, int> seen;
    for_each_record(bytes.data(), bytes.size(),
                    [&](std::uint8_t op, const std::uint8_t* c, std::size_t n, std::size_t) {
                        ++seen[static_cast<Op>(op)];
                        switch (static_cast<Op>(op)) {
                            case Op::kHeader: {
                                Header h;
                                parse_header(c, n, h);
                                EXPECT_EQ(h.library, "ltm test");
                                break;
                            }
                            case Op::kSchema: {
                                Schema s;
                                parse_schema(c, n, s);
                                EXPECT_EQ(s.data.size(), 38u);
                                EXPECT_EQ(s.name, "sensor_msgs::msg::dds_::PointCloud2_");
                                break;
                            }
                            case Op::kChannel: {
                                Channel ch;
                                parse_channel(c, n, ch);
                                EXPECT_EQ(ch.topic, "rt/robot/points");
                                EXPECT_EQ(ch.metadata.size(), 2u);
                                EXPECT_EQ(ch.metadata.at("offered_qos_profiles"), "- history: 1");
                                break;
                            }
                            case Op::kChunk: {
                                ChunkRecord k;
                                parse_chunk(c, n, k);
                                EXPECT_EQ(k.uncompressed_crc, 0x12345678u);
                                MessageRecord m;
                                parse_message(k.records + kRecordPrefix,
                                              k.records_size - kRecordPrefix, m);
                                EXPECT_EQ(m.sequence, 42u);
                                EXPECT_EQ(m.size, 5u);
                                EXPECT_EQ(m.data[3], 0xfe);
                                break;
                            }
                            case Op::kMessageIndex: {
                                std::uint16_t channel = 0;
                                std::vector<std::pair<std::uint64_t, std::uint64_t>> e;
                                parse_message_index(c, n, channel, e);
                                EXPECT_EQ(channel, 7u);
                                ASSERT_EQ(e.size(), 2u);
                                EXPECT_EQ(e[1].second, 39u);
                                break;
                            }
                            case Op::kChunkIndex: {
                                ChunkIndex ci;
                                parse_chunk_index(c, n, ci);
                                EXPECT_EQ(ci.message_index_offsets.at(9), 531u);
                                EXPECT_EQ(ci.compression, "zstd");
                                EXPECT_EQ(ci.uncompressed_size, 66u);
                                break;
                            }
                            case Op::kStatistics: {
                                Statistics st;
                                parse_statistics(c, n, st);
                                EXPECT_EQ(st.metadata_count, 5u);
                                EXPECT_EQ(st.channel_message_counts.at(7), 2u);
                                break;
                            }
                            case Op::kSummaryOffset: {
                                SummaryOffset so;
                                parse_summary_offset(c, n, so);
                                EXPECT_EQ(so.group_length, 70u);
                                break;
                            }
                            case Op::kFooter: {
                                Footer f;
                                parse_footer(c, n, f);
                                EXPECT_EQ(f.summary_crc, 0xcafef00du);
                                break;
                            }
                            default:
                                break;
                        }
                    });
    EXPECT_EQ(seen.size(), 10u);  // every kind written (DataEnd has no parser)
}

TEST(McapRecords, TruncatedContentNamesTheFieldAndOffset) {
    std::vector<std::uint8_t> out;
    Channel c;
    c.id = 1;
    c.topic = "points";
    c.message_encoding = "cdr";
    c.metadata = {{"k", "v"}};
    write_channel(out, c);
    const std::uint8_t* content = out.data() + kRecordPrefix;
    try {
        parse_channel(content, 10, c);  // ids (4), the topic's length (4), 2 of its 6 bytes
        FAIL();
    } catch (const common::FormatError& e) {
        EXPECT_STREQ(e.what(), "Channel record: topic at byte 8: truncated: needs 6 bytes, 2 left");
        EXPECT_EQ(describe(e), "topic at +8: truncated: needs 6 bytes, 2 left");
    }
    // Every cut is one error, never a read past the end.
    const std::size_t n = out.size() - kRecordPrefix;
    for (std::size_t cut = 0; cut < n; ++cut) {
        Channel d;
        EXPECT_THROW(parse_channel(content, cut, d), common::FormatError) << cut;
    }
    Channel whole;
    parse_channel(content, n, whole);
    EXPECT_TRUE(whole == c);
    // A chunk's records claiming more than there is.
    std::vector<std::uint8_t> chunk;
    ChunkRecord k;
    k.records_size = 100;
    write_chunk_prefix(chunk, k);
    chunk.resize(chunk.size() + 40);
    try {
        ChunkRecord r;
        parse_chunk(chunk.data() + kRecordPrefix, chunk.size() - kRecordPrefix, r);
        FAIL();
    } catch (const common::FormatError& e) {
        EXPECT_STREQ(e.what(),
                     "Chunk record: records at byte 40: truncated: needs 100 bytes, 40 left");
    }
}

TEST(McapRecords, RecordsOverrunningTheirBufferStopTheWalk) {
    std::vector<std::uint8_t> out;
    write_header(out, Header{"p", "l"});
    write_data_end(out, 1);
    out.resize(out.size() - 2);
    std::size_t calls = 0;
    try {
        for_each_record(
            out.data(), out.size(),
            [&](std::uint8_t, const std::uint8_t*, std::size_t, std::size_t) { ++calls; });
        FAIL();
    } catch (const common::FormatError& e) {
        EXPECT_EQ(calls, 1u);  // the Header
        EXPECT_STREQ(e.what(), "records: DataEnd record at byte 19: claims 4 bytes, only 2 remain");
    }
}

}  // namespace
}  // namespace ltm::recorder
