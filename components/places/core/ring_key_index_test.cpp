#include "places/core/ring_key_index.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace ltm::places {
namespace {

std::vector<float> brute_force(const std::vector<Eigen::VectorXf>& keys, const Eigen::VectorXf& q,
                               std::size_t k) {
    std::vector<float> d;
    for (const Eigen::VectorXf& key : keys) d.push_back((key - q).norm());
    std::sort(d.begin(), d.end());
    d.resize(std::min(k, d.size()));
    return d;
}

TEST(RingKeyIndex, NearestKeysMatchABruteForceOracle) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 10.0f);
    for (const std::size_t rebuild : {1u, 7u, 64u, 1000u}) {
        RingKeyIndex index(20, rebuild);
        std::vector<Eigen::VectorXf> keys;
        for (int i = 0; i < 600; ++i) {
            Eigen::VectorXf k(20);
            for (int d = 0; d < 20; ++d) k[d] = u(rng);
            ASSERT_TRUE(index.add(k, std::uint32_t(i)));
            keys.push_back(k);
            if (i % 97 != 0) continue;
            // Query in between additions: some keys are in the tree, some not yet.
            Eigen::VectorXf q(20);
            for (int d = 0; d < 20; ++d) q[d] = u(rng);
            const std::vector<RingKeyNeighbour> got = index.nearest(q, 10);
            const std::vector<float> want = brute_force(keys, q, 10);
            ASSERT_EQ(got.size(), want.size());
            for (std::size_t j = 0; j < got.size(); ++j) {
                EXPECT_NEAR(got[j].distance, want[j], 1e-4f) << "rebuild " << rebuild << " j " << j;
                EXPECT_NEAR((keys[got[j].item] - q).norm(), got[j].distance, 1e-4f);
            }
        }
    }
}

TEST(RingKeyIndex, SurvivesAMoveAndRefusesBadKeys) {
    RingKeyIndex a(3, 2);
    for (int i = 0; i < 9; ++i)
        ASSERT_TRUE(a.add(Eigen::Vector3f(float(i), 0, 0), std::uint32_t(100 + i)));
    EXPECT_FALSE(a.add(Eigen::Vector2f(1, 2), 0));
    EXPECT_FALSE(a.add(Eigen::Vector3f(std::nanf(""), 0, 0), 0));
    RingKeyIndex b = std::move(a);
    ASSERT_TRUE(b.add(Eigen::Vector3f(4.4f, 0, 0), 7));
    const std::vector<RingKeyNeighbour> n = b.nearest(Eigen::Vector3f(4.3f, 0, 0), 2);
    ASSERT_EQ(n.size(), 2u);
    EXPECT_EQ(n[0].item, 7u);
    EXPECT_EQ(n[1].item, 104u);
    EXPECT_TRUE(b.nearest(Eigen::Vector2f(0, 0), 3).empty());
}

}  // namespace
}  // namespace ltm::places
