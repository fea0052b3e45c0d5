#include "registration/core/preprocess.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>

#include "registration/core/test_scenes.hpp"

namespace ltm::registration {
namespace {

using Eigen::Vector3f;

std::set<VoxelKey> cells(const std::vector<Vector3f>& pts, double cell) {
    std::set<VoxelKey> out;
    for (const auto& p : pts) {
        Eigen::Vector3i v = Eigen::Vector3i::Zero();
        EXPECT_TRUE(voxel_coords(p, float(1.0 / cell), &v));
        out.insert(pack_key(v.x(), v.y(), v.z()));
    }
    return out;
}

common::PointCloud random_cloud(int n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-60.0f, 60.0f);
    common::PointCloud c;
    for (int i = 0; i < n; ++i) c.points.emplace_back(u(rng), u(rng), 0.1f * u(rng));
    return c;
}

TEST(Preprocess, DropsNonFiniteAndOutOfRangePointsAndCountsThem) {
    PreprocessConfig config;
    config.min_range = 2.0;
    config.max_range = 50.0;
    common::PointCloud c = random_cloud(5000, 1);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    c.points.emplace_back(nan, 0.0f, 0.0f);
    c.points.emplace_back(1.0f, inf, 0.0f);
    c.points.emplace_back(0.0f, 0.0f, -inf);
    c.points.emplace_back(0.5f, 0.5f, 0.0f);  // too close
    std::size_t in_range = 0, out_of_range = 0;
    for (const auto& p : c.points) {
        if (!p.allFinite()) continue;
        (p.norm() >= 2.0f && p.norm() <= 50.0f ? in_range : out_of_range)++;
    }
    Preprocessor pre(config, 1.0);
    PreprocessedScan out;
    pre.run(c, nullptr, &out);
    EXPECT_EQ(out.input_points, c.size());
    EXPECT_EQ(out.dropped_non_finite, 3u);
    EXPECT_EQ(out.dropped_range, out_of_range);
    for (const auto& p : out.map_points) {
        EXPECT_TRUE(p.allFinite());
        EXPECT_GE(p.norm(), 2.0f);
        EXPECT_LE(p.norm(), 50.0f);
    }
    EXPECT_LE(out.map_points.size(), in_range);
    EXPECT_FALSE(out.deskewed);
}

TEST(Preprocess, KeepsTheFirstPointOfEveryOccupiedCell) {
    PreprocessConfig config;
    config.min_range = 0.0;
    config.max_range = 1000.0;
    config.map_sample_fraction = 0.5;
    config.registration_sample_fraction = 2.0;
    const common::PointCloud c = random_cloud(20000, 2);
    Preprocessor pre(config, 1.0);
    PreprocessedScan out;
    pre.run(c, nullptr, &out);
    // Map grid 0.5 m: exactly one point per occupied cell, the first one in input order.
    EXPECT_EQ(cells(out.map_points, 0.5), cells(c.points, 0.5));
    EXPECT_EQ(out.map_points.size(), cells(c.points, 0.5).size());
    std::set<VoxelKey> seen;
    std::vector<Vector3f> first;
    for (const auto& p : c.points) {
        Eigen::Vector3i v = Eigen::Vector3i::Zero();
        ASSERT_TRUE(voxel_coords(p, 2.0f, &v));
        if (seen.insert(pack_key(v.x(), v.y(), v.z())).second) first.push_back(p);
    }
    EXPECT_EQ(out.map_points, first);
    // Registration grid 2 m: one map point per occupied cell.
    EXPECT_EQ(out.registration_points.size(), cells(out.map_points, 2.0).size());
    EXPECT_EQ(cells(out.registration_points, 2.0), cells(out.map_points, 2.0));
}

TEST(Preprocess, CapsTheRegistrationPoints) {
    PreprocessConfig config;
    config.min_range = 0.0;
    config.max_registration_points = 500;
    const common::PointCloud c = random_cloud(20000, 3);
    Preprocessor pre(config, 0.5);
    PreprocessedScan out;
    pre.run(c, nullptr, &out);
    EXPECT_EQ(out.registration_points.size(), 500u);
}

// The distance from each point to its nearest neighbour in `truth` (brute force), averaged.
double mean_nearest(const std::vector<Vector3f>& pts, const std::vector<Vector3f>& truth) {
    double sum = 0.0;
    for (const auto& p : pts) {
        float best = 1e30f;
        for (const auto& q : truth) best = std::min(best, (p - q).squaredNorm());
        sum += std::sqrt(best);
    }
    return sum / double(pts.size());
}

TEST(Preprocess, DeskewMovesPointsToTheScanStampFrame) {
    // A sensor turning 60 deg/s and driving 10 m/s: a 0.1 s revolution smears far points.
    const test::Scene scene = test::room_scene();
    test::ScanPattern pattern;
    pattern.rings = 16;
    pattern.azimuths = 360;
    pattern.noise = 0.0;
    const Eigen::Isometry3d start = test::make_pose(-5, 0, 1.5, 0, 0, 0);
    const Eigen::Isometry3d end = test::make_pose(-4, 0, 1.5, 0, 0, 6);
    const common::PointCloud raw = test::scan_scene(scene, pattern, start, end, 1, true, false);
    const common::PointCloud truth = test::scan_scene(scene, pattern, start, end, 1, true, true);
    ASSERT_TRUE(raw.has_time());
    const Vector6d velocity = se3_log(start.inverse() * end) / pattern.period;
    PreprocessConfig config;
    config.min_range = 0.5;
    config.map_sample_fraction = 0.1;
    Preprocessor pre(config, 1.0);
    PreprocessedScan skewed, deskewed;
    pre.run(raw, nullptr, &skewed);
    pre.run(raw, &velocity, &deskewed);
    EXPECT_FALSE(skewed.deskewed);
    ASSERT_TRUE(deskewed.deskewed);
    const double before = mean_nearest(skewed.map_points, truth.points);
    const double after = mean_nearest(deskewed.map_points, truth.points);
    EXPECT_GT(before, 0.1);
    EXPECT_LT(after, 0.01);
    // Without per-point times nothing is de-skewed.
    common::PointCloud timeless = raw;
    timeless.time.clear();
    PreprocessedScan out;
    pre.run(timeless, &velocity, &out);
    EXPECT_FALSE(out.deskewed);
}

}  // namespace
}  // namespace ltm::registration
