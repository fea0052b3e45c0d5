#include "recorder/core/mcap_recover.hpp"

#include <gtest/gtest.h>

#include "common/core/io_error.hpp"
#include "recorder/core/mcap_reader.hpp"
#include "recorder/core/test_util.hpp"

namespace ltm::recorder {
namespace {

std::vector<std::pair<std::uint64_t, std::vector<std::uint8_t>>> contents(const std::string& path) {
    McapReader r(path);
    std::vector<std::pair<std::uint64_t, std::vector<std::uint8_t>>> out;
    MessageCursor cur = r.messages();
    for (MessageView m; cur.next(m);)
        out.emplace_back(m.log_time, std::vector<std::uint8_t>(m.data, m.data + m.size));
    return out;
}

TEST(McapRecover, CutFilesBecomeCompleteFilesWithEveryIntactMessage) {
    test::TempDir dir("mcap_recover");
    const auto rec = test::make_recording(400, 3000, 21);
    for (const Compression comp : {Compression::kZstd, Compression::kLz4}) {
        McapWriterConfig config;
        config.chunk_size = 24 * 1024;
        config.compression = comp;
        const std::string full = dir.file("full.mcap");
        ASSERT_EQ(test::write_recording(full, rec, config), WriteStatus::kOk);
        const auto bytes = test::read_file(full);
        for (const double frac : {0.05, 0.33, 0.5, 0.77, 0.99}) {
            const std::size_t cut =
                static_cast<std::size_t>(frac * static_cast<double>(bytes.size()));
            const std::string in = dir.file("cut.mcap"), out = dir.file("recovered.mcap");
            test::write_file(in, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + cut));
            const auto before = contents(in);
            const RecoverResult res = recover(in, out);
            EXPECT_FALSE(res.problems.empty());
            EXPECT_EQ(res.messages, before.size());
            McapReader r(out);
            EXPECT_TRUE(r.problem().empty()) << r.problem();
            EXPECT_TRUE(r.indexed());
            const VerifyReport v = r.verify();
            EXPECT_TRUE(v.ok) << (v.problems.empty() ? "" : v.problems.front());
            EXPECT_EQ(contents(out), before) << "cut at " << cut;
            EXPECT_EQ(r.channels().size(), 3u);  // same ids and records as the input
            EXPECT_EQ(r.channels().at(1).metadata.at("qos"), "sensor");
            for (const auto& c : r.chunks()) EXPECT_EQ(c.compression, compression_name(comp));
        }
    }
}

TEST(McapRecover, RefusesToOverwriteItsInputAndNonMcap) {
    test::TempDir dir("mcap_recover_bad");
    const auto rec = test::make_recording(10, 100, 22);
    const std::string p = dir.file("a.mcap");
    ASSERT_EQ(test::write_recording(p, rec, McapWriterConfig{}), WriteStatus::kOk);
    EXPECT_THROW(recover(p, p), common::IoError);
    test::write_file(dir.file("text"), std::vector<std::uint8_t>(50, 'x'));
    EXPECT_THROW(recover(dir.file("text"), dir.file("b.mcap")), common::IoError);
}

}  // namespace
}  // namespace ltm::recorder
