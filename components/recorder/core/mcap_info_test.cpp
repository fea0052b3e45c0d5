#include "recorder/core/mcap_info.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "recorder/core/test_util.hpp"

namespace ltm::recorder {
namespace {

TEST(McapInfo, CountsDurationRatesAndTopics) {
    test::TempDir dir("mcap_info");
    McapWriterConfig config;
    config.chunk_size = 4096;
    config.compression = Compression::kLz4;
    const std::string path = dir.file("info.mcap");
    {
        McapWriter w(path, config);
        const auto s = w.add_schema("pkg::msg::dds_::Scan_", "omgidl", "struct Scan_ { long a; };");
        const auto scan = w.add_channel(s, "rt/scan");
        const auto odom = w.add_channel(0, "rt/odom", "json");
        w.add_channel(s, "rt/unused");
        const std::string payload(500, 'p');
        // 10 s: scans at 10 Hz (101 messages), odometry at 50 Hz (501 messages).
        for (int i = 0; i <= 500; ++i) {
            const std::uint64_t t = 5000000000ull + static_cast<std::uint64_t>(i) * 20000000ull;
            if (i % 5 == 0) {
                ASSERT_EQ(w.write(scan, t, t, payload.data(), payload.size()), WriteStatus::kOk);
            }
            ASSERT_EQ(w.write(odom, t, t, "{}", 2), WriteStatus::kOk);
        }
        ASSERT_EQ(w.close(), WriteStatus::kOk);
    }
    const McapInfo in = info(path);
    EXPECT_TRUE(in.problems.empty());
    EXPECT_TRUE(in.indexed);
    EXPECT_EQ(in.messages, 602u);
    EXPECT_DOUBLE_EQ(in.duration_s, 10.0);
    EXPECT_GT(in.chunks, 10u);
    EXPECT_EQ(in.chunks_by_compression.at("lz4"), in.chunks);
    EXPECT_GT(in.uncompressed_bytes, in.compressed_bytes);
    ASSERT_EQ(in.topics.size(), 3u);
    EXPECT_EQ(in.topics[0].topic, "rt/odom");
    EXPECT_EQ(in.topics[0].messages, 501u);
    EXPECT_NEAR(in.topics[0].rate_hz, 50.1, 1e-9);
    EXPECT_EQ(in.topics[1].topic, "rt/scan");
    EXPECT_EQ(in.topics[1].type, "pkg::msg::dds_::Scan_");
    EXPECT_EQ(in.topics[1].schema_encoding, "omgidl");
    EXPECT_EQ(in.topics[1].message_encoding, "cdr");
    EXPECT_EQ(in.topics[1].messages, 101u);
    EXPECT_EQ(in.topics[2].messages, 0u);
    std::ostringstream text;
    print_info(in, text);
    EXPECT_NE(text.str().find("rt/scan"), std::string::npos);
    EXPECT_NE(text.str().find("10.000 s"), std::string::npos);
    EXPECT_NE(text.str().find("complete, indexed"), std::string::npos);

    // The same numbers from a cut file, by linear scan.
    const auto bytes = test::read_file(path);
    test::write_file(dir.file("cut.mcap"),
                     std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 200));
    const McapInfo cut = info(dir.file("cut.mcap"));
    EXPECT_FALSE(cut.problems.empty());
    EXPECT_FALSE(cut.indexed);
    EXPECT_EQ(cut.messages, 602u);     // the cut only took summary bytes
    EXPECT_EQ(cut.topics.size(), 2u);  // rt/unused never reached the data section
}

}  // namespace
}  // namespace ltm::recorder
