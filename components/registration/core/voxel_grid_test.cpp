#include "registration/core/voxel_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

namespace ltm::registration {
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

// Points on a tilted plane with noise across it, so that voxels are usable.
std::vector<Vector3f> plane_points(int n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-8.0f, 8.0f);
    std::normal_distribution<float> noise(0.0f, 0.02f);
    std::vector<Vector3f> pts;
    for (int i = 0; i < n; ++i) {
        const float x = u(rng), y = u(rng);
        pts.emplace_back(x, y, 0.2f * x - 0.1f * y + 1.0f + noise(rng));
    }
    return pts;
}

TEST(VoxelGrid, FromDataReproducesEveryVoxelExactly) {
    VoxelGrid grid(0.5, VoxelConfig{});
    grid.integrate(plane_points(20000, 3), Vector3f(0, 0, 10), 1.0, all);
    grid.integrate(random_points(500, 8.0f, 4), Vector3f(0, 0, 10), 2.0, all);
    ASSERT_GT(grid.usable_voxels(), 300u);
    common::LocalMapData data;
    data.voxel_size = 0.5f;
    data.voxels = grid.to_data();
    std::size_t skipped = 99;
    const VoxelGrid loaded =
        VoxelGrid::from_data(data, VoxelConfig{}, VoxelConfig{}.min_planarity, &skipped);
    EXPECT_EQ(skipped, 0u);
    ASSERT_EQ(loaded.size(), grid.size());
    EXPECT_EQ(loaded.usable_voxels(), grid.usable_voxels());
    for (std::size_t i = 0; i < grid.size(); ++i) {
        ASSERT_EQ(loaded.keys()[i], grid.keys()[i]);
        const Surfel &a = grid.surfels()[i], &b = loaded.surfels()[i];
        EXPECT_EQ(b.centre, a.centre);
        if (a.usable) {
            EXPECT_EQ(b.normal, a.normal);
        }
        EXPECT_EQ(b.planarity, a.planarity);
        EXPECT_EQ(b.stability, a.stability);
        EXPECT_EQ(b.usable, a.usable);
        EXPECT_EQ(loaded.records()[i].created, grid.records()[i].created);
        EXPECT_EQ(loaded.records()[i].last_seen, grid.records()[i].last_seen);
        EXPECT_EQ(loaded.records()[i].observations, grid.records()[i].observations);
    }
    // The rebuilt sums carry the voxel's weight, centre, normal and planarity: integrating more
    // of the surface into the loaded grid and into the original gives nearly the same voxels.
    VoxelGrid more = loaded, original = grid;
    more.integrate(plane_points(5000, 5), Vector3f(0, 0, 10), 3.0, all);
    original.integrate(plane_points(5000, 5), Vector3f(0, 0, 10), 3.0, all);
    ASSERT_EQ(more.size(), original.size());
    std::size_t compared = 0, close = 0;
    for (std::size_t i = 0; i < original.size(); ++i) {
        const Surfel &a = original.surfels()[i], &b = more.surfels()[i];
        EXPECT_LT((a.centre - b.centre).norm(), 0.02f);
        if (!a.usable || !b.usable) continue;
        ++compared;
        EXPECT_GT(std::abs(a.normal.dot(b.normal)), 0.95f);
        close += std::abs(a.normal.dot(b.normal)) > 0.995f;
    }
    EXPECT_GT(compared, 250u);
    EXPECT_GT(double(close), 0.95 * double(compared));
}

TEST(VoxelGrid, FromDataLeavesOutBadVoxels) {
    common::LocalMapData data;
    data.voxel_size = 1.0f;
    common::VoxelData v;
    v.index = {1, 2, 3};
    v.centre = {1.5f, 2.5f, 3.5f};
    v.normal = {0, 0, 1};
    v.planarity = 0.9f;
    v.point_count = 10;
    data.voxels = {v, v};  // a repeated index
    data.voxels.push_back(v);
    data.voxels.back().index = {0, 0, 0};
    data.voxels.back().centre.x() = NAN;  // not finite
    data.voxels.push_back(v);
    data.voxels.back().index = {kVoxelKeyLimit + 5, 0, 0};  // out of the key range
    data.voxels.push_back(v);
    data.voxels.back().index = {-4, 0, 0};
    data.voxels.back().normal = {0, 0, 0.5f};  // not a unit normal: present, not usable
    std::size_t skipped = 0;
    const VoxelGrid g = VoxelGrid::from_data(data, VoxelConfig{}, 0.4, &skipped);
    EXPECT_EQ(skipped, 3u);
    EXPECT_EQ(g.size(), 2u);
    EXPECT_EQ(g.usable_voxels(), 1u);
}

TEST(VoxelGrid, CoarsenedMergesTheMomentsOfItsVoxels) {
    VoxelGrid fine(0.5, VoxelConfig{});
    const auto pts = plane_points(20000, 6);
    fine.integrate(pts, Vector3f(0, 0, 10), 1.0, all);
    VoxelGrid direct(1.5, VoxelConfig{});
    direct.integrate(pts, Vector3f(0, 0, 10), 1.0, all);
    const VoxelGrid coarse = fine.coarsened(3, VoxelConfig{});
    EXPECT_DOUBLE_EQ(coarse.voxel_size(), 1.5);
    EXPECT_EQ(coarse.size(), direct.size());
    std::size_t compared = 0;
    for (std::size_t i = 0; i < direct.size(); ++i) {
        const std::uint32_t j = coarse.find(unpack_key(direct.keys()[i]));
        ASSERT_NE(j, VoxelHash::kNone);
        const Surfel &a = direct.surfels()[i], &b = coarse.surfels()[j];
        EXPECT_LT((a.centre - b.centre).norm(), 0.05f);
        if (!a.usable) continue;
        ++compared;
        EXPECT_TRUE(b.usable);
        EXPECT_GT(std::abs(a.normal.dot(b.normal)), 0.9999f);
    }
    EXPECT_GT(compared, 80u);
}

// usable_neighbours (the usable flags mirrored in the hash) against for_each_neighbour filtered by
// the surfels' own flags, at random points over the grid.
void expect_usable_neighbours_match(const VoxelGrid& grid, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-9.0f, 9.0f);
    std::size_t found = 0;
    for (int q = 0; q < 2000; ++q) {
        const Vector3f x(u(rng), u(rng), 1.0f + 0.2f * u(rng));
        std::vector<std::uint32_t> want;
        grid.for_each_neighbour(x, [&](std::uint32_t i) {
            if (grid.surfels()[i].usable) want.push_back(i);
        });
        std::uint32_t got[27];
        const int n = grid.usable_neighbours(x, got);
        ASSERT_EQ(std::vector<std::uint32_t>(got, got + n), want);
        found += want.size();
    }
    EXPECT_GT(found, 0u);
}

TEST(VoxelGrid, UsableNeighboursFollowTheSurfelsThroughEveryWayAGridIsMade) {
    VoxelConfig config;
    VoxelGrid grid(0.5, config);
    // Voxels become usable over a few scans of a plane ...
    for (int scan = 0; scan < 3; ++scan) {
        grid.integrate(plane_points(4000, 10 + scan), Vector3f(0, 0, 10), scan, all);
        expect_usable_neighbours_match(grid, 20 + scan);
    }
    ASSERT_GT(grid.usable_voxels(), 100u);
    std::vector<bool> was_usable;
    for (const Surfel& s : grid.surfels()) was_usable.push_back(s.usable != 0);
    // ... and some stop being usable when points scattered about the plane land in them.
    std::vector<Vector3f> scatter = plane_points(20000, 5);
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> thick(-0.6f, 0.6f);
    for (Vector3f& p : scatter) p.z() += thick(rng);
    grid.integrate(scatter, Vector3f(0, 0, 10), 5.0, all);
    std::size_t lost = 0;
    for (std::size_t i = 0; i < was_usable.size(); ++i)
        lost += was_usable[i] && !grid.surfels()[i].usable;
    EXPECT_GT(lost, 10u);
    expect_usable_neighbours_match(grid, 30);
    // Loaded from plain data, coarsened, seeded from another grid.
    const VoxelGrid loaded = VoxelGrid::from_data(
        [&] {
            common::LocalMapData d;
            d.voxel_size = 0.5f;
            d.voxels = grid.to_data();
            return d;
        }(),
        config, config.min_planarity);
    ASSERT_GT(loaded.usable_voxels(), 0u);
    expect_usable_neighbours_match(loaded, 31);
    const VoxelGrid coarse = grid.coarsened(2, config);
    ASSERT_GT(coarse.usable_voxels(), 0u);
    expect_usable_neighbours_match(coarse, 32);
    VoxelGrid seeded(0.5, config);
    seeded.seed_from(grid, Eigen::Vector3i(1, -2, 0), [](const Vector3f& c) { return c.x() < 3; });
    ASSERT_GT(seeded.usable_voxels(), 0u);
    expect_usable_neighbours_match(seeded, 33);
}

}  // namespace
}  // namespace ltm::registration
