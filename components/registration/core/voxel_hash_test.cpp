#include "registration/core/voxel_hash.hpp"

#include <gtest/gtest.h>

#include <random>
#include <unordered_map>

namespace ltm::registration {
namespace {

TEST(VoxelHash, PackUnpackRoundTrip) {
    for (const Eigen::Vector3i& v : {Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(-1, 2, -3),
                                     Eigen::Vector3i(kVoxelKeyLimit, -kVoxelKeyLimit, 17)}) {
        EXPECT_EQ(unpack_key(pack_key(v.x(), v.y(), v.z())), v);
    }
    EXPECT_NE(pack_key(1, 0, 0), pack_key(0, 1, 0));
}

TEST(VoxelHash, VoxelCoordsFloorsAndRejectsOutOfRange) {
    Eigen::Vector3i v;
    ASSERT_TRUE(voxel_coords(Eigen::Vector3f(-0.1f, 0.0f, 1.9f), 1.0f, &v));
    EXPECT_EQ(v, Eigen::Vector3i(-1, 0, 1));
    EXPECT_FALSE(voxel_coords(Eigen::Vector3f(3e6f, 0, 0), 1.0f, &v));
    EXPECT_FALSE(voxel_coords(Eigen::Vector3f(NAN, 0, 0), 1.0f, &v));
}

TEST(VoxelHash, AgreesWithUnorderedMapThroughGrowthAndClear) {
    VoxelHash hash(4);
    std::unordered_map<VoxelKey, std::uint32_t> oracle;
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> c(-50, 50);
    for (int round = 0; round < 2; ++round) {
        for (std::uint32_t i = 0; i < 20000; ++i) {
            const VoxelKey k = pack_key(c(rng), c(rng), c(rng));
            const auto [value, inserted] = hash.insert(k, i);
            const auto [it, oracle_inserted] = oracle.emplace(k, i);
            ASSERT_EQ(inserted, oracle_inserted);
            ASSERT_EQ(value, it->second);
        }
        EXPECT_EQ(hash.size(), oracle.size());
        for (int i = 0; i < 5000; ++i) {
            const VoxelKey k = pack_key(c(rng), c(rng), c(rng) + 60 * (i % 2));
            const auto it = oracle.find(k);
            EXPECT_EQ(hash.find(k), it == oracle.end() ? VoxelHash::kNone : it->second);
        }
        hash.clear();
        oracle.clear();
        EXPECT_EQ(hash.size(), 0u);
        EXPECT_EQ(hash.find(pack_key(0, 0, 0)), VoxelHash::kNone);
    }
}

}  // namespace
}  // namespace ltm::registration
