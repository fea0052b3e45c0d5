// The asker keeps at most a window of chunks in flight, asks again only after nothing arrived for
// resend_after_s, and forgets chunks no longer missing.
#include "site/core/chunk_asker.hpp"

#include <gtest/gtest.h>

namespace ltm::site_sync {
namespace {

std::vector<ChunkRef> first(std::uint32_t n, std::uint32_t from = 0) {
    std::vector<ChunkRef> v;
    for (std::uint32_t i = from; i < from + n; ++i) v.push_back({0, i});
    return v;
}

TEST(ChunkAsker, AWindowInFlightAskedAgainOnlyWhenStalled) {
    ChunkAsker a(4, 2.0);
    EXPECT_EQ(a.due(first(10), 0.0), first(4));
    EXPECT_TRUE(a.due(first(10), 0.5).empty());  // the window is full
    a.received({0, 0}, 1.0);
    EXPECT_EQ(a.due(first(9, 1), 1.0), first(1, 4));  // one more
    // Progress keeps the outstanding ones from being asked again.
    a.received({0, 1}, 2.5);
    EXPECT_EQ(a.due(first(8, 2), 2.6), first(1, 5));
    EXPECT_EQ(a.asked_again(), 0u);
    // Nothing arrives for 2 s: everything outstanding is asked again.
    EXPECT_TRUE(a.due(first(8, 2), 4.0).empty());
    EXPECT_EQ(a.due(first(8, 2), 4.6), first(4, 2));
    EXPECT_EQ(a.asked_again(), 4u);
    // Chunks stored some other way (a resume) leave the window.
    EXPECT_EQ(a.due(first(6, 4), 4.7), first(2, 6));
    a.reset();
    EXPECT_EQ(a.due(first(3), 5.0), first(3));
}

}  // namespace
}  // namespace ltm::site_sync
