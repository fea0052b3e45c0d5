#include "maintenance/core/voxel_index.hpp"

#include <gtest/gtest.h>

#include <random>
#include <unordered_set>

namespace ltm::maintenance {
namespace {

TEST(VoxelIndex, FindsWhatABruteForceSetHolds) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> c(-300, 300);
    std::vector<registration::VoxelKey> keys;
    std::unordered_set<registration::VoxelKey> seen;
    VoxelIndex index;
    const auto key_of = [&](std::uint32_t i) { return keys[i]; };
    for (int n = 0; n < 20000; ++n) {
        const registration::VoxelKey k = registration::pack_key(c(rng), c(rng), c(rng) / 30);
        if (!seen.insert(k).second) {
            ASSERT_NE(index.find(k, key_of), VoxelIndex::kNone);
            continue;
        }
        ASSERT_EQ(index.find(k, key_of), VoxelIndex::kNone);
        keys.push_back(k);
        index.insert(k, std::uint32_t(keys.size() - 1), key_of);
    }
    for (std::uint32_t i = 0; i < keys.size(); ++i) ASSERT_EQ(index.find(keys[i], key_of), i);
    // 4 bytes a bucket at a load of at least one half.
    EXPECT_LE(index.memory_bytes(), keys.size() * 8 + 64);
    // Every other one dropped: the rest still found, the dropped not.
    std::vector<registration::VoxelKey> kept;
    for (std::size_t i = 0; i < keys.size(); i += 2) kept.push_back(keys[i]);
    const std::vector<registration::VoxelKey> all = keys;
    keys = kept;
    index.rebuild(keys.size(), key_of);
    EXPECT_EQ(index.size(), keys.size());
    for (std::uint32_t i = 0; i < keys.size(); ++i) ASSERT_EQ(index.find(keys[i], key_of), i);
    for (std::size_t i = 1; i < all.size(); i += 2)
        ASSERT_EQ(index.find(all[i], key_of), VoxelIndex::kNone);
}

}  // namespace
}  // namespace ltm::maintenance
