#include "link/core/send_window.hpp"

#include <gtest/gtest.h>

namespace ltm::link {
namespace {

// Sends whatever the window allows of [first, last] at time t; returns the seqs sent.
std::vector<std::uint64_t> pump(SendWindow& w, std::uint64_t first, std::uint64_t last, double t,
                                std::uint64_t bytes = 100) {
    std::vector<std::uint64_t> out;
    while (const auto s = w.next(first, last, t)) {
        w.sent(*s, bytes, t);
        out.push_back(*s);
    }
    return out;
}
using V = std::vector<std::uint64_t>;

TEST(SendWindow, SendsInOrderWithinTheWindow) {
    SendWindow w({250, 3.0, 24.0});
    EXPECT_EQ(pump(w, 1, 10, 0.0), (V{1, 2, 3}));  // 300 bytes >= 250: full
    w.on_ack(2, 7, 0.1);                           // first ack from base run 7: goes back to 3
    EXPECT_EQ(pump(w, 3, 10, 0.1), (V{3, 4, 5}));
    w.on_ack(5, 7, 0.2);
    EXPECT_EQ(w.acked(), 5u);
    EXPECT_EQ(pump(w, 6, 10, 0.2), (V{6, 7, 8}));
    EXPECT_EQ(w.stats().resent, 1u);  // seq 3 after the first ack
}

TEST(SendWindow, StalledAcknowledgementsMakeItGoBackWithBackoff) {
    SendWindow w({1000, 3.0, 24.0});
    w.on_ack(0, 1, 0.0);
    EXPECT_EQ(pump(w, 1, 4, 0.0), (V{1, 2, 3, 4}));
    w.on_ack(1, 1, 1.0);  // progress
    w.on_ack(1, 1, 2.0);
    EXPECT_TRUE(pump(w, 1, 4, 2.0).empty());
    w.on_ack(1, 1, 4.1);  // 3.1 s without progress: 2..4 again
    EXPECT_EQ(pump(w, 2, 4, 4.1), (V{2, 3, 4}));
    EXPECT_EQ(w.stats().go_backs, 1u);
    w.on_ack(1, 1, 8.0);  // the next go-back waits 6 s
    EXPECT_TRUE(pump(w, 2, 4, 8.0).empty());
    w.on_ack(1, 1, 10.2);
    EXPECT_EQ(pump(w, 2, 4, 10.2), (V{2, 3, 4}));
    EXPECT_EQ(w.stats().resent, 6u);
}

TEST(SendWindow, NoAcknowledgementMeansNoGoBack) {
    SendWindow w({1000, 3.0, 24.0});
    EXPECT_EQ(pump(w, 1, 3, 0.0), (V{1, 2, 3}));
    EXPECT_TRUE(pump(w, 1, 3, 100.0).empty());   // an outage: nothing sent into the void
    EXPECT_EQ(pump(w, 1, 5, 100.0), (V{4, 5}));  // new packets still go while the window allows
}

TEST(SendWindow, ARestartedBaseStationGetsWhatItLacksAtOnce) {
    SendWindow w({1000, 3.0, 24.0});
    w.on_ack(0, 1, 0.0);
    pump(w, 1, 6, 0.0);
    w.on_ack(6, 1, 0.5);
    EXPECT_EQ(w.acked(), 6u);
    pump(w, 1, 8, 0.6);
    w.on_ack(4, 2, 1.0);  // base run 2 journaled only up to 4
    EXPECT_EQ(w.stats().base_restarts, 1u);
    EXPECT_EQ(pump(w, 3, 8, 1.0), (V{5, 6, 7, 8}));
}

TEST(SendWindow, AcknowledgementsBackAfterALongSilenceResendAtOnce) {
    SendWindow w({1000, 3.0, 24.0});
    w.on_ack(0, 1, 0.0);
    EXPECT_EQ(pump(w, 1, 5, 0.0), (V{1, 2, 3, 4, 5}));
    w.on_ack(2, 1, 0.5);
    w.resume_after_silence(31.0);  // an outage: 3..5 went nowhere
    EXPECT_EQ(pump(w, 3, 5, 31.0), (V{3, 4, 5}));
    EXPECT_EQ(w.stats().go_backs, 1u);
}

TEST(SendWindow, ASilenceIsNotAStall) {
    SendWindow w({1000, 3.0, 24.0});
    w.on_ack(0, 1, 0.0);
    EXPECT_EQ(pump(w, 1, 3, 0.0), (V{1, 2, 3}));
    w.on_ack(1, 1, 0.5);
    w.on_ack(1, 1, 30.0);  // back after an outage: DDS repairs 2..3 now, no go-back yet
    EXPECT_TRUE(pump(w, 2, 3, 30.0).empty());
    w.on_ack(1, 1, 32.0);
    EXPECT_TRUE(pump(w, 2, 3, 32.0).empty());
    w.on_ack(1, 1, 33.1);  // 3 s heard without progress: a stall
    EXPECT_EQ(pump(w, 2, 3, 33.1), (V{2, 3}));
}

TEST(SendWindow, ReleasedOrDroppedSeqsAreSkipped) {
    SendWindow w({1000, 3.0, 24.0});
    EXPECT_EQ(pump(w, 5, 6, 0.0), (V{5, 6}));  // 1..4 no longer held
}

}  // namespace
}  // namespace ltm::link
