#include "odometry/core/voxel_grid.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>

namespace ltm::odometry {
namespace {

using Eigen::Vector3f;

std::vector<Vector3f> random_points(int n, float half, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-half, half);
    std::vector<Vector3f> pts;
    for (int i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), 0.3f * u(rng));
    return pts;
}

auto all = [](const Vector3f&) { return true; };

TEST(VoxelGrid, IntegrateAccumulatesPerVoxelAndKeepsTheLifeRecord) {
    VoxelGrid grid(1.0, VoxelConfig{});
    const auto pts = random_points(3000, 10.0f, 1);
    auto inside = [](const Vector3f& p) { return p.x() < 6.0f; };
    std::size_t kept = 0;
    for (const auto& p : pts) kept += inside(p);
    EXPECT_EQ(grid.integrate(pts, Vector3f(0, 0, 5), 1.0, inside), kept);
    // Brute force: count per voxel and mean.
    std::map<VoxelKey, std::pair<int, Eigen::Vector3d>> oracle;
    for (const auto& p : pts) {
        if (!inside(p)) continue;
        Eigen::Vector3i v = Eigen::Vector3i::Zero();
        ASSERT_TRUE(voxel_coords(p, 1.0f, &v));
        auto& e = oracle[pack_key(v.x(), v.y(), v.z())];
        if (e.first++ == 0) e.second.setZero();
        e.second += p.cast<double>();
    }
    ASSERT_EQ(grid.size(), oracle.size());
    for (std::size_t i = 0; i < grid.size(); ++i) {
        const auto& e = oracle.at(grid.keys()[i]);
        EXPECT_FLOAT_EQ(grid.records()[i].sums.weight, float(e.first));
        EXPECT_LT((grid.surfels()[i].centre.cast<double>() - e.second / e.first).norm(), 1e-4);
        EXPECT_EQ(grid.records()[i].observations, 1u);
        EXPECT_EQ(grid.records()[i].created, 1.0);
        EXPECT_EQ(grid.records()[i].last_seen, 1.0);
    }
    // A second scan touching only part of the grid.
    std::vector<Vector3f> second;
    for (const auto& p : pts) {
        if (inside(p) && second.size() < 10) second.push_back(p);
    }
    grid.integrate(second, Vector3f(0, 0, 5), 2.0, all);
    Eigen::Vector3i v = Eigen::Vector3i::Zero();
    ASSERT_TRUE(voxel_coords(second[0], 1.0f, &v));
    const std::uint32_t i = grid.find(v);
    ASSERT_NE(i, VoxelHash::kNone);
    EXPECT_EQ(grid.records()[i].observations, 2u);
    EXPECT_EQ(grid.records()[i].created, 1.0);
    EXPECT_EQ(grid.records()[i].last_seen, 2.0);
}

TEST(VoxelGrid, NeighboursAreTheOccupiedVoxelsOfThe3x3x3Block) {
    VoxelGrid grid(0.5, VoxelConfig{});
    grid.integrate(random_points(2000, 6.0f, 2), Vector3f(0, 0, 5), 1.0, all);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-6.5f, 6.5f);
    for (int q = 0; q < 200; ++q) {
        const Vector3f x(u(rng), u(rng), 0.3f * u(rng));
        std::set<std::uint32_t> got;
        grid.for_each_neighbour(x, [&](std::uint32_t i) { EXPECT_TRUE(got.insert(i).second); });
        Eigen::Vector3i vx = Eigen::Vector3i::Zero();
        ASSERT_TRUE(voxel_coords(x, 2.0f, &vx));
        std::set<std::uint32_t> want;
        for (std::uint32_t i = 0; i < grid.size(); ++i) {
            if ((unpack_key(grid.keys()[i]) - vx).cwiseAbs().maxCoeff() <= 1) want.insert(i);
        }
        EXPECT_EQ(got, want);
    }
}

}  // namespace
}  // namespace ltm::odometry
