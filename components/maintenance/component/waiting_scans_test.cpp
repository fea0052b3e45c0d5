// The maintenance queue's memory bound (issue 28 item 2): the byte counts, the bound, and a full
// queue noted once until it has room again.
#include "maintenance/component/waiting_scans.hpp"

#include <gtest/gtest.h>

namespace ltm::maintenance {
namespace {

constexpr std::size_t kMiB = 1 << 20;

TEST(WaitingScans, TheDefaultBoundKeepsAVlp32QueueAndCutsA64BeamOne) {
    // 128 MiB (max_queue_mb's default) and 300 scans: a VLP-32C's packed scan waits in ~0.35
    // MiB (the bench's day 1: 257 scans in 90.5 MiB), an HDL-64E's in ~0.9 MiB.
    WaitingScans vlp(300, 128 * kMiB);
    for (int i = 0; i < 300; ++i) {
        ASSERT_FALSE(vlp.over_bytes(kMiB * 35 / 100)) << i;
        vlp.add(kMiB * 35 / 100, kMiB * 6 / 10);
    }
    EXPECT_EQ(vlp.count(), 300u);
    WaitingScans hdl(300, 128 * kMiB);
    int fitted = 0;
    while (!hdl.over_bytes(kMiB * 9 / 10)) {
        hdl.add(kMiB * 9 / 10, 2 * kMiB);
        ++fitted;
    }
    EXPECT_EQ(fitted, 142);  // 142 x 0.9 MiB = 127.8 MiB
    EXPECT_LE(hdl.bytes(), 128 * kMiB);
    EXPECT_EQ(hdl.peak_unpacked_bytes(), 142 * 2 * kMiB);
}

TEST(WaitingScans, BytesAndPeaksFollowTheQueue) {
    WaitingScans q(10, 0);  // no byte bound
    EXPECT_FALSE(q.over_bytes(1u << 30));
    q.add(100, 200);
    q.add(50, 120);
    q.add(70, 90);
    EXPECT_EQ(q.bytes(), 220u);
    q.remove_front();  // the worker took the oldest
    EXPECT_EQ(q.bytes(), 120u);
    q.remove_back();  // the newest refused
    EXPECT_EQ(q.bytes(), 50u);
    EXPECT_EQ(q.count(), 1u);
    EXPECT_EQ(q.peak_count(), 3u);
    EXPECT_EQ(q.peak_bytes(), 220u);
    EXPECT_EQ(q.peak_unpacked_bytes(), 410u);
    q.remove_front();
    q.remove_front();  // nothing waits: nothing happens
    EXPECT_EQ(q.bytes(), 0u);
    // A single scan larger than the bound is never refused room when nothing waits.
    WaitingScans small(10, 100);
    EXPECT_FALSE(small.over_bytes(1000));
    small.add(1000, 1000);
    EXPECT_TRUE(small.over_bytes(1));
}

TEST(WaitingScans, AFullQueueIsNotedOnceUntilItHasRoomAgain) {
    WaitingScans q(4, 1000);
    for (int i = 0; i < 4; ++i) q.add(200, 400);
    EXPECT_TRUE(q.over_bytes(300));
    EXPECT_TRUE(q.mark_full());   // logged
    EXPECT_FALSE(q.mark_full());  // still the same episode
    q.remove_front();             // 3 scans, 600 B: not yet half of both bounds
    EXPECT_FALSE(q.mark_full());
    q.remove_front();  // 2 scans, 400 B: room again
    EXPECT_TRUE(q.mark_full());
    EXPECT_EQ(q.full_times(), 2u);
}

}  // namespace
}  // namespace ltm::maintenance
