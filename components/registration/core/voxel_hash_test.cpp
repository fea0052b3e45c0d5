#include "registration/core/voxel_hash.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
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

TEST(VoxelHash, FloorInKeyRangeIsStdFloorWithTheRangeCheck) {
    // The old definition: floor, then |floor| < the key limit.
    const auto reference = [](float x, std::int32_t* out) {
        const float f = std::floor(x);
        if (!(std::abs(f) < float(kVoxelKeyLimit))) return false;
        *out = std::int32_t(f);
        return true;
    };
    std::vector<float> xs = {0.0f,
                             -0.0f,
                             0.5f,
                             -0.5f,
                             1.0f,
                             -1.0f,
                             -1e-30f,
                             1e-30f,
                             2.9999998f,
                             -2.9999998f,
                             std::numeric_limits<float>::quiet_NaN(),
                             std::numeric_limits<float>::infinity(),
                             -std::numeric_limits<float>::infinity(),
                             3e9f,
                             -3e9f};
    for (const float edge :
         {float(kVoxelKeyLimit), float(1 - kVoxelKeyLimit), float(-kVoxelKeyLimit)}) {
        for (const float d : {-1.0f, -0.5f, -0.0625f, 0.0f, 0.0625f, 0.5f, 1.0f})
            xs.push_back(edge + d);
        xs.push_back(std::nextafter(edge, 0.0f));
        xs.push_back(std::nextafter(edge, 2.0f * edge));
    }
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> wide(-2.2e6f, 2.2e6f), narrow(-40.0f, 40.0f);
    for (int i = 0; i < 100000; ++i) xs.push_back(i % 2 ? wide(rng) : narrow(rng));
    for (const float x : xs) {
        std::int32_t got = 12345, want = 12345;
        const bool ok = floor_in_key_range(x, &got);
        ASSERT_EQ(ok, reference(x, &want)) << x;
        if (ok) {
            ASSERT_EQ(got, want) << x;
        }
    }
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

TEST(VoxelHash, TagsStayWithTheirKeysThroughGrowthAndClear) {
    VoxelHash hash(4);
    std::unordered_map<VoxelKey, std::pair<std::uint32_t, std::uint32_t>> oracle;  // value, tag
    std::mt19937 rng(12);
    std::uniform_int_distribution<int> c(-40, 40);
    for (std::uint32_t i = 0; i < 30000; ++i) {
        const VoxelKey k = pack_key(c(rng), c(rng), c(rng));
        const auto [value, inserted] = hash.insert(k, i);
        if (inserted) oracle[k] = {value, 0};
        // Tag some keys (and untag some again) while the table grows under them.
        if (i % 3 == 0) {
            const std::uint32_t tag = i % 2;
            hash.set_tag(k, tag);
            oracle[k].second = tag;
        }
    }
    std::size_t tagged = 0;
    for (const auto& [k, e] : oracle) {
        ASSERT_EQ(hash.find(k), e.first);
        ASSERT_EQ(hash.find_tagged(k), e.second != 0 ? e.first : VoxelHash::kNone);
        tagged += e.second != 0;
    }
    EXPECT_GT(tagged, 1000u);
    EXPECT_LT(tagged, oracle.size());
    // Keys that are not there, beside ones that are (long probe runs included).
    for (int i = 0; i < 5000; ++i) {
        const VoxelKey k = pack_key(c(rng), c(rng), c(rng) + 100);
        EXPECT_EQ(hash.find_tagged(k), VoxelHash::kNone);
    }
    // After clear an entry inserted again starts untagged.
    const VoxelKey k = oracle.begin()->first;
    hash.set_tag(k, 1);
    hash.clear();
    EXPECT_EQ(hash.find_tagged(k), VoxelHash::kNone);
    hash.insert(k, 7);
    EXPECT_EQ(hash.find_tagged(k), VoxelHash::kNone);
    hash.set_tag(k, 1);
    EXPECT_EQ(hash.find_tagged(k), 7u);
}

}  // namespace
}  // namespace ltm::registration
