#include "places/core/local_features.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "common/core/kitti_io.hpp"
#include "common/core/trajectory_io.hpp"
#include "places/core/local_feature_matching.hpp"
#include "registration/core/ransac_alignment.hpp"
#include "registration/core/se3.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::places {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using Eigen::Vector3f;
using registration::test::make_pose;

constexpr double kDeg = M_PI / 180.0;

std::vector<Vector3f> transformed(const std::vector<Vector3f>& points, const Isometry3d& T) {
    std::vector<Vector3f> out;
    out.reserve(points.size());
    for (const Vector3f& p : points) out.push_back((T * p.cast<double>()).cast<float>());
    return out;
}

// Points within +-half_fov_deg of the x axis (a narrow sensor such as a Livox Avia).
std::vector<Vector3f> wedge(const std::vector<Vector3f>& points, double half_fov_deg) {
    std::vector<Vector3f> out;
    for (const Vector3f& p : points) {
        if (std::abs(std::atan2(p.y(), p.x())) <= half_fov_deg * kDeg) out.push_back(p);
    }
    return out;
}

std::vector<Vector3f> street_scan(const Isometry3d& T_world_sensor, std::uint32_t seed) {
    static const registration::test::Scene scene = registration::test::street_scene();
    registration::test::ScanPattern pattern;
    pattern.rings = 64;
    pattern.azimuths = 1024;
    pattern.max_range = 60.0;
    return registration::test::scan_scene(scene, pattern, T_world_sensor, T_world_sensor, seed)
        .points;
}

double yaw_error(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

struct Outcome {
    std::size_t matches = 0, right = 0;  // right: the target within 0.75 spacing of T * query
    double median_yaw_error = 0.0;       // over the right ones [rad]
    std::optional<registration::RansacAlignment> ransac;
};

// Matches the query to the target and runs RANSAC on the matched positions.
Outcome evaluate(const LocalFeatures& query, const LocalFeatures& target,
                 const Isometry3d& T_target_query, double spacing,
                 const LocalFeatureMatchConfig& match_config = {}) {
    Outcome o;
    const std::vector<FeatureMatch> matches = match_local_features(query, target, match_config);
    o.matches = matches.size();
    std::vector<Vector3d> src, dst;
    std::vector<double> yaw_errors;
    const double yaw = std::atan2(T_target_query.linear()(1, 0), T_target_query.linear()(0, 0));
    for (const FeatureMatch& m : matches) {
        src.push_back(query.positions[m.query]);
        dst.push_back(m.target_position);
        const Vector3d d = T_target_query * query.positions[m.query] - target.positions[m.target];
        if (d.head<2>().norm() < 0.75 * spacing) {
            ++o.right;
            yaw_errors.push_back(yaw_error(m.yaw, yaw));
        }
    }
    if (!yaw_errors.empty()) {
        std::nth_element(yaw_errors.begin(), yaw_errors.begin() + yaw_errors.size() / 2,
                         yaw_errors.end());
        o.median_yaw_error = yaw_errors[yaw_errors.size() / 2];
    }
    registration::RansacAlignmentConfig rc;
    rc.inlier_distance = 0.5 * spacing;
    o.ransac = registration::ransac_align(src, dst, rc);
    return o;
}

void expect_pose(const Outcome& o, const Isometry3d& T, double max_t, double max_deg) {
    ASSERT_TRUE(o.ransac.has_value());
    const Isometry3d e = T.inverse() * o.ransac->T_target_source;
    EXPECT_LT(e.translation().norm(), max_t);
    EXPECT_LT(registration::rotation_angle(e) / kDeg, max_deg);
}

TEST(LocalFeatures, ConfigErrorsNameTheKey) {
    LocalFeatureConfig c;
    EXPECT_FALSE(validate(c).has_value());
    c.sample_spacing = 0.0;
    ASSERT_TRUE(validate(c).has_value());
    EXPECT_EQ(validate(c)->key, "sample_spacing");
    EXPECT_THROW(make_local_features({}, c), common::ConfigError);
    LocalFeatureMatchConfig m;
    EXPECT_FALSE(validate(m).has_value());
    m.per_query = 0;
    ASSERT_TRUE(validate(m).has_value());
    EXPECT_EQ(validate(m)->key, "per_query");
    EXPECT_THROW(match_local_features({}, {}, m), common::ConfigError);
    EXPECT_THROW(make_local_features({}, LocalFeatureConfig{}, Vector3d::Zero(), -1.0),
                 common::ConfigError);
}

TEST(LocalFeatures, SamplesLieOnTheGroundLattice) {
    // A flat floor at z = -1.8 with a car-sized box and a tall block: samples only on the floor.
    registration::test::Scene s;
    s.add_quad({0, 0, -1.8}, {40, 0, 0}, {0, 40, 0});
    s.add_box({6, -4, -1.8}, {12, 4, -0.3});
    s.add_box({-20, 5, -1.8}, {-10, 15, 6.0});
    registration::test::ScanPattern pattern;
    pattern.rings = 64;
    pattern.fov_up = 20.0;
    const auto cloud = registration::test::scan_scene(s, pattern, Isometry3d::Identity(),
                                                      Isometry3d::Identity(), 1);
    std::vector<Vector3f> points = cloud.points;
    points.push_back(Vector3f(NAN, 0.0f, 0.0f));
    LocalFeatureConfig c;
    const LocalFeatures f = make_local_features(points, c);
    ASSERT_GT(f.size(), 20u);
    ASSERT_EQ(f.descriptors.size(), f.size());
    for (std::size_t i = 0; i < f.size(); ++i) {
        const Vector3d& p = f.positions[i];
        EXPECT_NEAR(p.z(), -1.8, 0.1) << p.transpose();
        EXPECT_NEAR(std::remainder(p.x(), c.sample_spacing), 0.0, 1e-9);
        EXPECT_NEAR(std::remainder(p.y(), c.sample_spacing), 0.0, 1e-9);
        EXPECT_LE(p.head<2>().norm(), c.max_range);
        const bool on_box = p.x() > 6.5 && p.x() < 11.5 && std::abs(p.y()) < 3.5;
        const bool on_block = p.x() > -19.5 && p.x() < -10.5 && p.y() > 5.5 && p.y() < 14.5;
        EXPECT_FALSE(on_box || on_block) << p.transpose();
        EXPECT_EQ(f.descriptors[i].rings, c.rings);
        EXPECT_EQ(f.descriptors[i].sectors, c.sectors);
        EXPECT_EQ(f.descriptors[i].kind, places::ScanContextKind::kMeanVariance);
    }
    c.max_samples = 7;
    const LocalFeatures few = make_local_features(points, c);
    ASSERT_EQ(few.size(), 7u);  // spread out: on the 8- and 4-spacing sub-lattices
    for (std::size_t i = 0; i < few.size(); ++i) {
        EXPECT_EQ(few.positions[i], f.positions[i]);
        EXPECT_NEAR(std::remainder(few.positions[i].x(), 4.0 * c.sample_spacing), 0.0, 1e-9);
        EXPECT_NEAR(std::remainder(few.positions[i].y(), 4.0 * c.sample_spacing), 0.0, 1e-9);
    }
    EXPECT_TRUE(make_local_features({}, c).empty());
}

TEST(LocalFeatures, MapRegionSamplesAroundTheCentre) {
    const std::vector<Vector3f> points = street_scan(make_pose(60, 0, 1.8, 0, 0, 0), 2);
    std::vector<Vector3f> world = transformed(points, make_pose(60, 0, 1.8, 0, 0, 0));
    LocalFeatureConfig c;
    const Vector3d centre(70.0, 1.0, 0.0);
    const LocalFeatures f = make_local_features(world, c, centre, 12.0);
    ASSERT_GT(f.size(), 5u);
    for (const Vector3d& p : f.positions) {
        EXPECT_LE((p - centre).head<2>().norm(), 12.0);
        EXPECT_NEAR(p.z(), 0.0, 0.1);
    }
}

TEST(LocalFeatures, SameCloudUnderYawAndShift) {
    const std::vector<Vector3f> target_points = street_scan(make_pose(60, 0, 1.8, 0, 0, 0), 3);
    const LocalFeatureConfig c;
    const LocalFeatures target = make_local_features(target_points, c);
    for (const double yaw_deg : {37.0, -100.0, 180.0}) {
        const Isometry3d T_target_query = make_pose(4.0, -3.0, 0.3, 0, 0, yaw_deg);
        const LocalFeatures query =
            make_local_features(transformed(target_points, T_target_query.inverse()), c);
        ASSERT_GT(query.size(), 30u);
        const Outcome o = evaluate(query, target, T_target_query, c.sample_spacing);
        SCOPED_TRACE(yaw_deg);
        EXPECT_GT(double(o.right), 0.5 * double(query.size()));
        EXPECT_LT(o.median_yaw_error, 5.0 * kDeg);
        expect_pose(o, T_target_query, 0.3, 1.0);
    }
}

TEST(LocalFeatures, NarrowScanAgainstAMapRegion) {
    // The target: voxel centres of scans along the street (every direction seen); the query: one
    // 70-degree scan from elsewhere, turned.
    std::vector<Vector3f> map;
    for (const double x : {40.0, 48.0, 56.0, 64.0, 72.0, 80.0}) {
        const Isometry3d T = make_pose(x, 0.5, 1.8, 0, 0, 0);
        const auto scan = transformed(street_scan(T, std::uint32_t(x)), T);
        map.insert(map.end(), scan.begin(), scan.end());
    }
    const LocalFeatureConfig c;
    const Vector3d centre(60.0, 0.0, 0.0);
    LocalFeatureConfig map_config = c;
    map_config.max_samples = 1000;
    const LocalFeatures target = make_local_features(map, map_config, centre, 40.0);
    const Isometry3d T_world_query = make_pose(61.3, -1.2, 1.7, 0, 0, 150.0);
    Isometry3d T_target_query = T_world_query;
    for (const double half_fov : {180.0, 35.0}) {
        LocalFeatureConfig qc = c;
        const LocalFeatures query =
            make_local_features(wedge(street_scan(T_world_query, 9), half_fov), qc);
        SCOPED_TRACE(half_fov);
        ASSERT_GT(query.size(), 10u);
        const Outcome o = evaluate(query, target, T_target_query, c.sample_spacing);
        EXPECT_GT(double(o.right), 0.3 * double(query.size()));
        expect_pose(o, T_target_query, 0.3, 1.0);
    }
}

TEST(LocalFeatures, MatchFiltersAndRefinement) {
    const std::vector<Vector3f> points = street_scan(make_pose(60, 0, 1.8, 0, 0, 0), 4);
    const LocalFeatureConfig c;
    const LocalFeatures target = make_local_features(points, c);
    const LocalFeatures query =
        make_local_features(transformed(points, make_pose(1, 2, 0, 0, 0, 30).inverse()), c);
    ASSERT_GT(query.size(), 20u);
    LocalFeatureMatchConfig m;
    const auto all = match_local_features(query, target, m);
    std::vector<int> per_query(query.size(), 0), per_target(target.size(), 0);
    for (std::size_t k = 0; k < all.size(); ++k) {
        ++per_query[all[k].query];
        if (k > 0) {
            EXPECT_LE(all[k - 1].distance, all[k].distance);  // sorted
        }
        // The refined position stays within half a spacing (an axis) of the target sample.
        const Vector3d d = all[k].target_position - target.positions[all[k].target];
        EXPECT_LE(d.head<2>().cwiseAbs().maxCoeff(), 0.5 * c.sample_spacing + 1e-9);
        EXPECT_LE(std::abs(all[k].yaw), M_PI);
    }
    for (const int n : per_query) EXPECT_LE(n, m.per_query);
    m.per_query = 1;
    const auto best = match_local_features(query, target, m);
    EXPECT_LE(best.size(), query.size());
    m.per_query = 3;
    m.mutual = true;
    for (const FeatureMatch& f : match_local_features(query, target, m)) {
        EXPECT_EQ(++per_target[f.target], 1);  // each target kept for its best query only
    }
    m.mutual = false;
    m.max_distance = 1e-6;
    EXPECT_TRUE(match_local_features(query, target, m).empty());
    // Descriptors of another shape are not matched; without a spacing nothing is refined.
    LocalFeatureConfig other = c;
    other.rings = 6;
    const LocalFeatures odd = make_local_features(points, other);
    EXPECT_TRUE(match_local_features(query, odd, LocalFeatureMatchConfig{}).empty());
    LocalFeatures plain = target;
    plain.sample_spacing = 0.0;
    for (const FeatureMatch& f : match_local_features(query, plain, LocalFeatureMatchConfig{})) {
        EXPECT_EQ(f.target_position, plain.positions[f.target]);
    }
}

TEST(LocalFeatures, RealKittiScanTurnedAndShifted) {
    // Frame 0 of the kitti00_mini fixture, turned and shifted, against frames 1 and 2 merged into
    // frame 0's place (SemanticKITTI poses) and voxelised like a map.
    const std::string dir = LTM_SOURCE_DIR "/tests/fixtures/kitti00_mini";
    const auto files = common::list_kitti_scans(dir);
    ASSERT_EQ(files.size(), 3u);
    const auto poses =
        common::camera_to_lidar_poses(common::read_kitti_poses(dir + "/poses_semantickitti.txt"),
                                      common::read_kitti_calib_tr(dir + "/calib.txt"));
    std::vector<Vector3f> map;
    for (std::size_t k = 1; k < 3; ++k) {
        const auto s =
            transformed(common::read_kitti_bin(files[k]).points, poses[0].inverse() * poses[k]);
        map.insert(map.end(), s.begin(), s.end());
    }
    LocalFeatureConfig map_config;
    map_config.max_samples = 1000;
    const LocalFeatures target = make_local_features(map, map_config, Vector3d::Zero(), 40.0);
    const std::vector<Vector3f> scan = common::read_kitti_bin(files[0]).points;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> yaw(-180.0, 180.0), shift(-5.0, 5.0);
    for (int trial = 0; trial < 3; ++trial) {
        const Isometry3d T_target_query = make_pose(shift(rng), shift(rng), 0.2, 0, 0, yaw(rng));
        const LocalFeatures query =
            make_local_features(transformed(scan, T_target_query.inverse()), LocalFeatureConfig{});
        SCOPED_TRACE(trial);
        ASSERT_GT(query.size(), 50u);
        const Outcome o = evaluate(query, target, T_target_query, map_config.sample_spacing);
        EXPECT_GT(double(o.right), 0.5 * double(query.size()));
        EXPECT_LT(o.median_yaw_error, 5.0 * kDeg);
        expect_pose(o, T_target_query, 0.5, 1.0);
    }
}

}  // namespace
}  // namespace ltm::places
