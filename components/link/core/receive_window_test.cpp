#include "link/core/receive_window.hpp"

#include <gtest/gtest.h>

namespace ltm::link {
namespace {

JournalRecord rec(std::uint64_t seq) {
    JournalRecord r;
    r.seq = seq;
    return r;
}
std::vector<std::uint64_t> seqs(const std::vector<JournalRecord>& v) {
    std::vector<std::uint64_t> out;
    for (const auto& r : v) out.push_back(r.seq);
    return out;
}
using V = std::vector<std::uint64_t>;

TEST(ReceiveWindow, InOrderPassesThrough) {
    ReceiveWindow w;
    EXPECT_EQ(seqs(w.offer(rec(1), 1)), V{1});
    EXPECT_EQ(seqs(w.offer(rec(2), 1)), V{2});
    EXPECT_EQ(w.through(), 2u);
}

TEST(ReceiveWindow, OutOfOrderIsHeldAndDuplicatesDropped) {
    ReceiveWindow w;
    EXPECT_TRUE(w.offer(rec(3), 1).empty());
    EXPECT_TRUE(w.offer(rec(2), 1).empty());
    EXPECT_TRUE(w.offer(rec(3), 1).empty());  // held twice: a duplicate
    EXPECT_EQ(seqs(w.offer(rec(1), 1)), (V{1, 2, 3}));
    EXPECT_TRUE(w.offer(rec(2), 1).empty());  // delivered already
    EXPECT_EQ(w.stats().duplicates, 2u);
    EXPECT_EQ(w.through(), 3u);
}

TEST(ReceiveWindow, WhatTheSenderDroppedIsSkipped) {
    ReceiveWindow w;
    w.offer(rec(1), 1);
    EXPECT_TRUE(w.offer(rec(5), 2).empty());         // 2..4 may still come
    EXPECT_EQ(seqs(w.offer(rec(6), 5)), (V{5, 6}));  // the robot no longer holds 2..4
    EXPECT_EQ(w.stats().lost, 3u);
}

TEST(ReceiveWindow, ARestartedBaseStationStartsAfterItsJournal) {
    ReceiveWindow w(10);
    EXPECT_TRUE(w.offer(rec(9), 1).empty());
    EXPECT_EQ(seqs(w.offer(rec(11), 1)), V{11});
}

TEST(ReceiveWindow, HeldPacketsAreBounded) {
    ReceiveWindow w(0, 2);
    w.offer(rec(3), 1);
    w.offer(rec(4), 1);
    EXPECT_TRUE(w.offer(rec(5), 1).empty());
    EXPECT_EQ(w.stats().overflow, 1u);
    EXPECT_EQ(seqs(w.offer(rec(1), 1)), V{1});  // the next seq always fits
    EXPECT_EQ(seqs(w.offer(rec(2), 1)), (V{2, 3, 4}));
    EXPECT_EQ(seqs(w.offer(rec(5), 1)), V{5});  // resent
}

}  // namespace
}  // namespace ltm::link
