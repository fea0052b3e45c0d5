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

// The first point of each cell in input order, by brute force over the points kept by the crop.
std::vector<Vector3f> first_per_cell(const std::vector<Vector3f>& pts, double cell,
                                     double min_range, double max_range) {
    std::set<VoxelKey> seen;
    std::vector<Vector3f> first;
    for (const auto& p : pts) {
        if (!p.allFinite() || p.norm() < min_range || p.norm() > max_range) continue;
        Eigen::Vector3i v = Eigen::Vector3i::Zero();
        if (!voxel_coords(p, float(1.0 / cell), &v)) continue;
        if (seen.insert(pack_key(v.x(), v.y(), v.z())).second) first.push_back(p);
    }
    return first;
}

TEST(Preprocess, ARingOrderedScanKeepsTheFirstPointOfEveryCell) {
    // A scan stored ring by ring, as a spinning LiDAR's: runs of neighbours in one map cell, with
    // points out of range and not finite inside the runs, and every ring crossing the cells of
    // the ring before it (a cell met again later, not just after itself).
    PreprocessConfig config;
    config.min_range = 2.0;
    config.max_range = 40.0;
    config.map_sample_fraction = 0.5;
    config.registration_sample_fraction = 1.5;
    common::PointCloud c;
    for (int ring = 0; ring < 16; ++ring) {
        const float elevation = -0.25f + 0.02f * float(ring);
        for (int k = 0; k < 3000; ++k) {
            const float azimuth = 2.0f * float(M_PI) * float(k) / 3000.0f;
            const float range = 6.0f + 3.0f * std::sin(3.0f * azimuth) + 0.5f * float(ring % 3);
            Vector3f p(range * std::cos(azimuth), range * std::sin(azimuth),
                       1.8f + range * std::tan(elevation));
            if (k % 97 == 5) p = Vector3f(50.0f, 0.0f, 0.0f);  // beyond max_range
            if (k % 89 == 7) p = Vector3f(0.5f, 0.0f, 0.0f);   // within min_range
            if (k % 101 == 9) p.x() = std::numeric_limits<float>::quiet_NaN();
            c.points.push_back(p);
        }
    }
    Preprocessor pre(config, 1.0);
    PreprocessedScan out;
    pre.run(c, nullptr, &out);
    const std::vector<Vector3f> want = first_per_cell(c.points, 0.5, 2.0, 40.0);
    ASSERT_GT(want.size(), 1000u);
    EXPECT_LT(want.size(), c.points.size() / 4);  // long runs in one cell
    EXPECT_EQ(out.map_points, want);
    EXPECT_EQ(out.registration_points, first_per_cell(out.map_points, 1.5, 0.0, 1e9));
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

// Map points only (the localisation's): the same map points and mid-sweep pose, de-skewed as
// before, no registration points.
TEST(Preprocess, MapPointsOnlyGivesTheSameMapPoints) {
    const test::Scene scene = test::room_scene();
    test::ScanPattern pattern;
    pattern.rings = 16;
    pattern.azimuths = 360;
    const Eigen::Isometry3d start = test::make_pose(-5, 0, 1.5, 0, 0, 0);
    const Eigen::Isometry3d end = test::make_pose(-4, 0, 1.5, 0, 0, 6);
    const common::PointCloud raw = test::scan_scene(scene, pattern, start, end, 1, true, false);
    const Vector6d velocity = se3_log(start.inverse() * end) / pattern.period;
    PreprocessConfig config;
    Preprocessor full(config, 0.5), only(config, 0.5);
    only.set_map_points_only(true);
    PreprocessedScan a, b;
    full.run(raw, &velocity, &a);
    only.run(raw, &velocity, &b);
    ASSERT_TRUE(a.deskewed);
    EXPECT_TRUE(b.deskewed);
    EXPECT_FALSE(a.registration_points.empty());
    EXPECT_TRUE(b.registration_points.empty());
    ASSERT_EQ(a.map_points.size(), b.map_points.size());
    for (std::size_t i = 0; i < a.map_points.size(); ++i)
        ASSERT_EQ(a.map_points[i], b.map_points[i]) << i;
    EXPECT_TRUE(a.T_stamp_mid.isApprox(b.T_stamp_mid, 0.0));
}

TEST(Preprocess, DeskewReportsTheMidSweepPoseItAssumed) {
    // Points of a sweep over 0.1 s, each in the sensor frame of its own time, taken while moving
    // at `truth`; de-skewed with a velocity 0.5 m/s and 3 deg/s off. In the frame at the stamp the
    // error grows with the time, half a sweep's worth on average: a registration of these points
    // moves the stamp pose by that. In the frame in the middle of the sweep it averages out.
    Vector6d truth, wrong;
    truth << 3.0, 0.2, 0.0, 0.0, 0.0, 0.5;
    wrong = truth;
    wrong(0) += 0.5;
    wrong(5) += 3.0 * M_PI / 180.0;
    common::PointCloud raw = random_cloud(3000, 5);
    std::vector<Vector3f> at_stamp;
    for (std::size_t i = 0; i < raw.points.size(); ++i) {
        raw.time.push_back(float(0.1 * double(i) / double(raw.points.size() - 1)));
        at_stamp.push_back(
            (se3_exp(raw.time[i] * truth) * raw.points[i].cast<double>()).cast<float>());
    }
    PreprocessConfig config;
    config.min_range = 0.0;
    config.max_range = 1000.0;
    config.map_sample_fraction = 0.001;  // keeps every point, in order
    Preprocessor pre(config, 1.0);
    PreprocessedScan out;
    pre.run(raw, &wrong, &out);
    ASSERT_TRUE(out.deskewed);
    ASSERT_EQ(out.map_points.size(), raw.points.size());
    EXPECT_TRUE(out.T_stamp_mid.isApprox(se3_exp(0.05 * wrong), 1e-6));
    const Eigen::Isometry3f stamp_to_mid = out.T_stamp_mid.inverse().cast<float>();
    const Eigen::Isometry3f truth_to_mid = se3_exp(0.05 * truth).inverse().cast<float>();
    Eigen::Vector3d off_stamp = Eigen::Vector3d::Zero(), off_mid = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < at_stamp.size(); ++i) {
        off_stamp += (out.map_points[i] - at_stamp[i]).cast<double>();
        off_mid += (stamp_to_mid * out.map_points[i] - truth_to_mid * at_stamp[i]).cast<double>();
    }
    off_stamp /= double(at_stamp.size());
    off_mid /= double(at_stamp.size());
    EXPECT_NEAR(off_stamp.x(), 0.05 * 0.5, 0.005);  // half a sweep of the velocity error
    EXPECT_LT(off_mid.norm(), 0.1 * off_stamp.norm());
    // De-skewed again with the true velocity: the true points and mid-sweep pose.
    pre.redeskew_map_points(truth, &out);
    EXPECT_TRUE(out.T_stamp_mid.isApprox(se3_exp(0.05 * truth), 1e-6));
    for (std::size_t i = 0; i < at_stamp.size(); i += 100)
        EXPECT_LT((out.map_points[i] - at_stamp[i]).norm(), 1e-3) << i;
    // Not de-skewed (no velocity, or no times): the scan is taken at its stamp.
    pre.run(raw, nullptr, &out);
    EXPECT_TRUE(out.T_stamp_mid.isApprox(Eigen::Isometry3d::Identity()));
    raw.time.clear();
    pre.run(raw, &wrong, &out);
    EXPECT_TRUE(out.T_stamp_mid.isApprox(Eigen::Isometry3d::Identity()));
}

}  // namespace
}  // namespace ltm::registration
