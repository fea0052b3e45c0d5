#include "maintenance/core/voxel_history.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ltm::maintenance {
namespace {

double mean_slot(const VoxelHistory::Entries& h) {
    double sum = 0.0, views = 0.0;
    for (int k = 0; k < h.n; ++k) {
        const double w = double(h.e[std::size_t(k)].hits) + h.e[std::size_t(k)].free;
        sum += w * h.e[std::size_t(k)].slot;
        views += w;
    }
    return sum / views;
}

TEST(VoxelHistory, KeepsEveryViewWithinItsCapacity) {
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> step(0, 3);
    std::bernoulli_distribution hit(0.7);
    VoxelHistory h;
    EXPECT_TRUE(h.empty());
    std::uint32_t hits = 0, free = 0;
    double sum = 0.0;
    std::int32_t slot = 1000;
    for (int v = 0; v < 500; ++v) {
        slot += step(rng);
        const bool is_hit = hit(rng);
        h.add(slot, is_hit, VoxelHistory::kCapacity);
        (is_hit ? hits : free) += 1;
        sum += slot;
        const VoxelHistory::Entries e = h.entries();
        ASSERT_LE(e.n, VoxelHistory::kCapacity);
        for (int k = 1; k < e.n; ++k)
            ASSERT_LT(e.e[std::size_t(k - 1)].slot, e.e[std::size_t(k)].slot);
    }
    EXPECT_EQ(histogram_total(h.hit_histogram()), hits);
    EXPECT_EQ(histogram_total(h.free_histogram()), free);
    // Merging at weighted means keeps the mean, up to the rounding of each merge to a slot (1 %
    // of the 730 slots spanned).
    EXPECT_NEAR(mean_slot(h.entries()), sum / 500.0, 7.3);
    EXPECT_GE(h.entries().e[std::size_t(h.entries().n - 1)].slot, slot - 20) << "recent views";
}

TEST(VoxelHistory, AShortRunOfHitsKeepsItsOwnEntry) {
    // A car passing: seen through for 40 slots, hit for 3, seen through for 40. Entries of one kind
    // merge first, so the hits stay apart from the free views around them.
    VoxelHistory h;
    for (int s = 0; s < 83; ++s)
        for (int v = 0; v < 2; ++v) h.add(s, s >= 40 && s < 43, VoxelHistory::kCapacity);
    const SlotHistogram hits = h.hit_histogram();
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_NEAR(hits[0].slot, 41, 1);
    EXPECT_EQ(hits[0].count, 6);
    const VoxelHistory::Entries e = h.entries();
    for (int k = 0; k < e.n; ++k) {
        if (e.e[std::size_t(k)].hits > 0) {
            EXPECT_EQ(e.e[std::size_t(k)].free, 0) << k;
        }
    }
}

TEST(VoxelHistory, FewerEntriesWhenAsked) {
    VoxelHistory h;
    for (int s = 0; s < 20; ++s) h.add(10 * s, s % 2 == 0, 3);
    EXPECT_EQ(h.entries().n, 3);
    EXPECT_EQ(histogram_total(h.hit_histogram()) + histogram_total(h.free_histogram()), 20u);
}

TEST(VoxelHistory, PacksNegativeAndFarSlots) {
    VoxelHistory::Entries in;
    in.n = 3;
    in.e[0] = {-5, 1, 0};
    in.e[1] = {70000, 4095, 2};
    in.e[2] = {-5 + std::int32_t(VoxelHistory::kMaxOffset), 0, 9};
    in.first_hit = -5;
    in.last_hit = 70000;
    VoxelHistory h;
    h.assign(in);
    const VoxelHistory::Entries out = h.entries();
    ASSERT_EQ(out.n, 3);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(out.e[std::size_t(k)].slot, in.e[std::size_t(k)].slot) << k;
        EXPECT_EQ(out.e[std::size_t(k)].hits, in.e[std::size_t(k)].hits) << k;
        EXPECT_EQ(out.e[std::size_t(k)].free, in.e[std::size_t(k)].free) << k;
    }
    EXPECT_EQ(out.first_hit, -5);
    EXPECT_EQ(h.hit_span(), VoxelHistory::kMaxSpan) << "saturated";
    // A view beyond 2^23 slots from the first hit lands on the farthest slot it can hold.
    h.add(-5 + std::int32_t(VoxelHistory::kMaxOffset) + 1000, true, VoxelHistory::kCapacity);
    const VoxelHistory::Entries far = h.entries();
    EXPECT_EQ(far.e[std::size_t(far.n - 1)].slot, -5 + std::int32_t(VoxelHistory::kMaxOffset));
    EXPECT_EQ(far.e[std::size_t(far.n - 1)].hits, 1u);
}

TEST(VoxelHistory, TheHitSpanIsExactThoughEntriesMerge) {
    VoxelHistory h;
    EXPECT_EQ(h.hit_span(), 0u);
    for (int s = 0; s < 10; ++s) h.add(s, false, VoxelHistory::kCapacity);
    for (int s = 10; s < 50; ++s) h.add(s, true, VoxelHistory::kCapacity);
    for (int s = 50; s < 90; ++s) h.add(s, false, VoxelHistory::kCapacity);
    EXPECT_EQ(h.entries().first_hit, 10);
    EXPECT_EQ(h.hit_span(), 39u);
    const SlotHistogram hits = h.hit_histogram();
    EXPECT_LT(hits.back().slot - hits.front().slot, 39) << "what the merged entries would say";
}

TEST(VoxelHistory, CountsHalveTogetherPastTheirLimit) {
    VoxelHistory h;
    for (int v = 0; v < 3000; ++v) {  // 6000 hits and 3000 free views: 2 to 1
        h.add(7, true, VoxelHistory::kCapacity);
        h.add(7, true, VoxelHistory::kCapacity);
        h.add(9, false, VoxelHistory::kCapacity);
    }
    const VoxelHistory::Entries e = h.entries();
    ASSERT_EQ(e.n, 2);
    EXPECT_LE(e.e[0].hits, VoxelHistory::kMaxCount);
    EXPECT_NEAR(double(e.e[0].hits) / double(e.e[1].free), 2.0, 0.01);
}

// The histograms a pass reads, into reused vectors: the hit histogram, and every view's by slot
// as the hit and free histograms merged (what judge_voxel read before).
TEST(VoxelHistory, HistogramsIntoReusedRoomAreTheHitAndTheMergedViews) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> step(0, 5);
    std::bernoulli_distribution hit(0.4);
    SlotHistogram hits{{-7, 3}}, views{{1, 1}, {2, 2}};  // stale content: cleared
    for (int voxel = 0; voxel < 50; ++voxel) {
        VoxelHistory h;
        std::int32_t slot = 100 * voxel;
        for (int v = 0; v < 5 + voxel * 7; ++v) {
            slot += step(rng);
            h.add(slot, hit(rng), VoxelHistory::kCapacity);
        }
        h.histograms(&hits, &views);
        const SlotHistogram want_hits = h.hit_histogram(), free = h.free_histogram();
        ASSERT_EQ(hits.size(), want_hits.size());
        for (std::size_t k = 0; k < hits.size(); ++k) {
            EXPECT_EQ(hits[k].slot, want_hits[k].slot);
            EXPECT_EQ(hits[k].count, want_hits[k].count);
        }
        SlotHistogram want_views = want_hits;
        for (const SlotCount& f : free) add_to_histogram(want_views, f.slot, f.count, 100);
        ASSERT_EQ(views.size(), want_views.size()) << voxel;
        for (std::size_t k = 0; k < views.size(); ++k) {
            EXPECT_EQ(views[k].slot, want_views[k].slot);
            EXPECT_EQ(views[k].count, want_views[k].count);
        }
        EXPECT_EQ(histogram_total(views), histogram_total(want_hits) + histogram_total(free));
    }
}

}  // namespace
}  // namespace ltm::maintenance
