#include "recorder/async/async_mcap_writer.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <thread>

#include "recorder/core/mcap_reader.hpp"
#include "recorder/core/test_util.hpp"

namespace ltm::recorder {
namespace {

TEST(AsyncMcapWriter, WritesEverythingFromSeveralProducers) {
    test::TempDir dir("mcap_async");
    const std::string path = dir.file("async.mcap");
    McapWriterConfig config;
    config.chunk_size = 64 * 1024;
    AsyncMcapWriter w(std::make_unique<McapWriter>(path, config));
    const auto s = w.add_schema("S", "omgidl", "struct S { long a; };");
    const auto a = w.add_channel(s, "rt/a");
    const auto b = w.add_channel(0, "rt/b", "json");
    EXPECT_THROW(w.add_channel(99, "rt/c"), std::invalid_argument);
    auto produce = [&](std::uint16_t ch, std::uint64_t offset) {
        std::vector<std::uint8_t> payload(3000);
        for (std::uint64_t i = 0; i < 500; ++i) {
            payload[0] = static_cast<std::uint8_t>(i);
            const std::uint64_t t = 2 * i + offset;
            if (i % 2) {
                ASSERT_TRUE(w.push(ch, t, t, payload.data(), payload.size()));
            } else {
                ASSERT_TRUE(w.push(ch, t, t, std::vector<std::uint8_t>(payload)));
            }
        }
    };
    std::thread t1(produce, a, 0), t2(produce, b, 1);
    t1.join();
    t2.join();
    const AsyncWriterStats st = w.close();
    EXPECT_FALSE(st.failed) << st.error;
    EXPECT_EQ(st.accepted, 1000u);
    EXPECT_EQ(st.written, 1000u);
    EXPECT_EQ(st.dropped(), 0u);
    EXPECT_EQ(st.writer.messages, 1000u);
    EXPECT_EQ(st.queued_messages, 0u);
    EXPECT_EQ(st.queued_bytes, 0u);
    McapReader r(path);
    EXPECT_TRUE(r.verify().ok);
    MessageCursor cur = r.messages();
    std::uint64_t expect = 0;
    for (MessageView m; cur.next(m); ++expect) {
        EXPECT_EQ(m.log_time, expect);
        EXPECT_EQ(m.channel->topic, expect % 2 ? "rt/b" : "rt/a");
        EXPECT_EQ(m.data[0], static_cast<std::uint8_t>(expect / 2));
    }
    EXPECT_EQ(expect, 1000u);
    EXPECT_FALSE(w.push(a, 1, 1, "x", 1));  // after close: counted, not queued
    EXPECT_EQ(w.stats().dropped_after_failure, 1u);
}

TEST(AsyncMcapWriter, AnIdleWriterClosesItsOpenChunk) {
    // A slow topic alone never fills a chunk: after idle_flush_s without messages the writer
    // thread writes the open chunk, so a kill -9 loses at most that long.
    test::TempDir dir("mcap_async_idle");
    AsyncWriterConfig config;
    config.idle_flush_s = 0.01;
    AsyncMcapWriter w(std::make_unique<McapWriter>(dir.file("idle.mcap")), config);
    const auto ch = w.add_channel(0, "rt/slow", "json");
    ASSERT_TRUE(w.push(ch, 1, 1, "{}", 2));
    // Wait for the condition (bounded), not for a time.
    for (int i = 0; i < 100000 && w.stats().writer.chunks == 0; ++i) std::this_thread::yield();
    for (int i = 0; i < 1000 && w.stats().writer.chunks == 0; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    EXPECT_EQ(w.stats().writer.chunks, 1u);
    McapReader r(dir.file("idle.mcap"));  // still open: read by linear scan
    EXPECT_EQ(r.statistics().message_count, 1u);
    EXPECT_EQ(w.close().written, 1u);
}

TEST(AsyncMcapWriter, CountsAndReportsWhatTheQueueCannotHold) {
    test::TempDir dir("mcap_async_drop");
    AsyncWriterConfig config;
    config.max_queue_bytes = 1000;  // a bigger message never fits: dropped deterministically
    std::vector<std::string> reports;
    AsyncMcapWriter w(std::make_unique<McapWriter>(dir.file("drop.mcap")), config,
                      [&](const std::string& line) { reports.push_back(line); });
    const auto ch = w.add_channel(0, "rt/big", "json");
    std::vector<std::uint8_t> big(5000, 1);
    for (int i = 0; i < 3; ++i) EXPECT_FALSE(w.push(ch, 1, 1, big.data(), big.size()));
    EXPECT_TRUE(w.push(ch, 2, 2, "ok", 2));
    const AsyncWriterStats st = w.close();
    EXPECT_EQ(st.dropped_queue_full, 3u);
    EXPECT_EQ(st.dropped_by_topic.at("rt/big"), 3u);
    EXPECT_EQ(st.written, 1u);
    ASSERT_FALSE(reports.empty());  // close() reports what was not yet reported
    EXPECT_NE(reports.back().find("3 in total"), std::string::npos) << reports.back();
    EXPECT_NE(reports.back().find("rt/big 3"), std::string::npos) << reports.back();
}

TEST(AsyncMcapWriter, FullDiskStopsRecordingKeepsFileValidAndCountsTheRest) {
    test::TempDir dir("mcap_async_full");
    const std::string path = dir.file("full.mcap");
    McapWriterConfig wc;
    wc.chunk_size = 16 * 1024;
    wc.compression = Compression::kNone;
    rlimit old{};
    ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
    const auto old_handler = signal(SIGXFSZ, SIG_IGN);
    rlimit small = old;
    small.rlim_cur = 150 * 1024;
    ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
    std::vector<std::string> reports;
    AsyncWriterStats st;
    {
        AsyncMcapWriter w(std::make_unique<McapWriter>(path, wc), AsyncWriterConfig{},
                          [&](const std::string& line) { reports.push_back(line); });
        const auto ch = w.add_channel(0, "rt/x", "json");
        std::vector<std::uint8_t> payload(2000, 3);
        for (std::uint64_t i = 0; i < 300; ++i) w.push(ch, i, i, payload.data(), payload.size());
        st = w.close();
    }
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, old_handler);
    EXPECT_TRUE(st.failed);
    EXPECT_NE(st.error.find("disk full"), std::string::npos) << st.error;
    // Every push is accounted for: written, refused by the failing write, or dropped.
    EXPECT_EQ(st.written + 1 + st.dropped_after_failure + st.dropped_queue_full, 300u);
    EXPECT_EQ(st.writer.messages + st.writer.lost_messages, st.written + 1);
    EXPECT_GT(st.dropped(), 0u);
    ASSERT_FALSE(reports.empty());
    bool told = false;
    for (const auto& r : reports) told = told || r.find("disk full") != std::string::npos;
    EXPECT_TRUE(told);
    McapReader r(path);
    const VerifyReport v = r.verify();
    EXPECT_TRUE(v.ok) << (v.problems.empty() ? "" : v.problems.front());
    EXPECT_EQ(v.messages, st.writer.messages);
    EXPECT_GT(v.messages, 10u);
}

}  // namespace
}  // namespace ltm::recorder
