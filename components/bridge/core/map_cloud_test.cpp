#include "bridge/core/map_cloud.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace ltm::bridge {
namespace {

TEST(Decimate, CentroidOfEachCell) {
    double leaf = 1.0;
    const auto out =
        decimate({{0.1f, 0.1f, 0.1f}, {0.3f, 0.5f, 0.9f}, {2.5f, 0.5f, 0.5f}}, 10, leaf);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_DOUBLE_EQ(leaf, 1.0);
    bool found = false;
    for (const auto& p : out) found |= (p - Eigen::Vector3f(0.2f, 0.3f, 0.5f)).norm() < 1e-6f;
    EXPECT_TRUE(found);
}

TEST(Decimate, NeverMoreThanMaxPointsAndStaysOnTheSurface) {
    // A 100 m x 100 m wall of 360 000 points (a brute-force check of the bound and of where the
    // decimated points lie: on the plane, inside the wall).
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.f, 100.f);
    std::vector<Eigen::Vector3f> wall;
    for (int i = 0; i < 360000; ++i) wall.emplace_back(u(rng), 3.0f, u(rng));
    double leaf = 0.1;
    const auto out = decimate(wall, 20000, leaf);
    EXPECT_LE(out.size(), 20000u);
    EXPECT_GT(out.size(), 10000u);  // the leaf grows no more than it needs to
    EXPECT_GT(leaf, 0.7);
    for (const auto& p : out) {
        ASSERT_NEAR(p.y(), 3.0f, 1e-4f);
        ASSERT_TRUE(p.x() >= 0.f && p.x() <= 100.f && p.z() >= 0.f && p.z() <= 100.f);
    }
}

TEST(Decimate, SkipsNonFinitePoints) {
    double leaf = 0.5;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(decimate({{nan, 0.f, 0.f}, {1.f, 1.f, 1.f}}, 10, leaf).size(), 1u);
}

Eigen::Isometry3d shift(double x, double y) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, 0);
    return T;
}

TEST(MapCloud, OdometryFrameUntilAGraphThenTheGraphsAnchors) {
    MapCloud cloud(MapCloudConfig{100, 0.01});
    EXPECT_FALSE(cloud.dirty());
    cloud.set_local_map(1, shift(10, 0), {{1.f, 0.f, 0.f}});
    cloud.set_local_map(2, shift(20, 0), {{2.f, 0.f, 0.f}});
    ASSERT_TRUE(cloud.dirty());
    auto c = cloud.build();
    EXPECT_FALSE(cloud.dirty());
    EXPECT_FALSE(c.in_map_frame);
    ASSERT_EQ(c.points.size(), 2u);
    std::sort(c.points.begin(), c.points.end(), [](auto& a, auto& b) { return a.x() < b.x(); });
    EXPECT_NEAR(c.points[0].x(), 11.f, 1e-5f);
    EXPECT_NEAR(c.points[1].x(), 22.f, 1e-5f);

    // The graph moved map 1 by +5 in y and knows nothing of map 2 yet: map 2 follows the
    // correction of the newest map the graph placed.
    cloud.set_graph({{1, shift(10, 5)}});
    c = cloud.build();
    EXPECT_TRUE(c.in_map_frame);
    std::sort(c.points.begin(), c.points.end(), [](auto& a, auto& b) { return a.x() < b.x(); });
    EXPECT_NEAR(c.points[0].y(), 5.f, 1e-5f);
    EXPECT_NEAR(c.points[1].x(), 22.f, 1e-5f);
    EXPECT_NEAR(c.points[1].y(), 5.f, 1e-5f);
    EXPECT_EQ(c.input_points, 2u);

    // A newer snapshot of map 2 replaces the old one.
    cloud.set_local_map(2, shift(20, 0), {{3.f, 0.f, 0.f}, {4.f, 0.f, 0.f}});
    EXPECT_EQ(cloud.build().points.size(), 3u);
    EXPECT_EQ(cloud.local_maps(), 2u);
}

// A long day adds local maps with its distance (here 60 laps of one 20 m square, a map a lap):
// the points kept stay within the bound, coarsened, and the cloud still covers every map.
TEST(MapCloud, TheLocalMapsKeptStayWithinTheirBoundOverALongDay) {
    MapCloudConfig config;
    config.max_points = 1000;
    config.leaf_m = 0.1;
    MapCloud cloud(config);  // keeps at most 4000 points
    std::vector<Eigen::Vector3f> lap;
    for (int i = 0; i < 400; ++i)  // a 20 m wall every 5 cm, 1 m high at 4 heights
        for (int h = 0; h < 4; ++h) lap.emplace_back(0.05f * float(i), 0.0f, 0.25f * float(h));
    for (std::uint64_t id = 0; id < 60; ++id) {
        cloud.set_local_map(id, shift(0.0, 0.0), lap);
        ASSERT_LE(cloud.kept_points(), 4000u) << id;
    }
    EXPECT_GT(cloud.kept_leaf_m(), 0.1);
    EXPECT_LE(cloud.memory_bytes(), 4000 * sizeof(Eigen::Vector3f) + 60 * 200);
    const MapCloud::Cloud c = cloud.build();
    ASSERT_FALSE(c.points.empty());
    float lo = 1e9f, hi = -1e9f;
    for (const Eigen::Vector3f& p : c.points) {
        lo = std::min(lo, p.x());
        hi = std::max(hi, p.x());
    }
    EXPECT_LT(lo, 1.5f);  // the wall's both ends are still drawn
    EXPECT_GT(hi, 18.5f);
    // Within the bound nothing is decimated: the first maps are kept as they came.
    MapCloud small(config);
    small.set_local_map(1, shift(0.0, 0.0), lap);
    EXPECT_EQ(small.kept_points(), lap.size());
    EXPECT_EQ(small.kept_leaf_m(), 0.0);
}

}  // namespace
}  // namespace ltm::bridge
