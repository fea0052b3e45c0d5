#include "mapping/core/odometry_bridge.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mapping/core/loop_verifier.hpp"
#include "mapping/core/test_data.hpp"

namespace ltm::mapping {
namespace {

double rot_deg(const Eigen::Isometry3d& T) {
    return Eigen::AngleAxisd(T.linear()).angle() * 180.0 / M_PI;
}

TEST(OdometryBridge, RebuiltMapReproducesTheVoxelsAndTheRegistration) {
    const std::vector<Eigen::Vector3f> scene = test::synthetic_scene(21);
    common::PoseList poses;
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (int i = 0; i < 5; ++i) {
        poses.push_back(test::xy_yaw(2.0 * i, 0.3 * i, 10.0 * i));
        scans.push_back(test::view(scene, poses.back(), 50.0));
    }
    const Eigen::Isometry3d anchor = test::xy_yaw(0.37, -0.21, 33.0);  // not on the lattice
    const common::LocalMapData data = test::build_local_map(5, anchor, scans, poses, 1.0, 40.0);
    ASSERT_GT(data.voxels.size(), 1000u);
    const RegistrationTarget t = rebuild_registration_target(data, 0.4, 3);
    EXPECT_EQ(t.skipped_voxels, 0u);
    EXPECT_EQ(t.fine.size(), data.voxels.size());
    ASSERT_TRUE(t.coarse.has_value());
    EXPECT_GT(t.coarse->usable_voxels(), 50u);
    // Every usable voxel comes back with its centre (within the 1 cm inset) and its normal.
    std::size_t usable = 0;
    for (const common::VoxelData& v : data.voxels) {
        if (!(v.planarity >= 0.4f) || v.normal.squaredNorm() == 0.0f) continue;
        ++usable;
        const std::uint32_t i = t.fine.find(v.index);
        ASSERT_NE(i, odometry::VoxelHash::kNone);
        const odometry::Surfel& s = t.fine.surfels()[i];
        EXPECT_LT((s.centre - v.centre).norm(), 0.01f * std::sqrt(3.0f) + 1e-4f);
        EXPECT_GT(std::abs(s.normal.dot(v.normal)), 0.999f);
        EXPECT_TRUE(s.usable);
    }
    EXPECT_EQ(t.fine.usable_voxels(), usable);
    EXPECT_GT(usable, 500u);

    // Registering a new view against the rebuilt map lands where the scene says.
    const Eigen::Isometry3d truth = test::xy_yaw(5.0, 1.0, 25.0);
    const std::vector<Eigen::Vector3f> scan = test::view(scene, truth, 50.0);
    LoopVerifierConfig cfg;
    LoopVerifier verifier(cfg);
    const Eigen::Isometry3d T_anchor_truth = anchor.inverse() * truth;
    const LoopVerification v =
        verifier.verify(scan, 5, data, T_anchor_truth * test::xy_yaw(0.8, -0.6, 4.0));
    EXPECT_TRUE(v.accepted) << v.reason;
    const Eigen::Isometry3d err = T_anchor_truth.inverse() * v.T_anchor_lidar;
    EXPECT_LT(err.translation().norm(), 0.05);
    EXPECT_LT(rot_deg(err), 0.3);
}

TEST(OdometryBridge, LocalMapAndKeyframeConversions) {
    const std::vector<Eigen::Vector3f> scene = test::synthetic_scene(22);
    const Eigen::Isometry3d anchor = test::xy_yaw(3.3, -1.2, 50.0);
    odometry::LocalMap map(7, anchor, 1.0, 30.0, odometry::VoxelConfig(), 5.0);
    const Eigen::Vector3f sensor = (anchor.translation() - map.origin()).cast<float>();
    std::vector<Eigen::Vector3f> pts = test::view(scene, anchor, 30.0);
    for (Eigen::Vector3f& p : pts) p = (anchor * p.cast<double>() - map.origin()).cast<float>();
    map.integrate(pts, sensor, 5.5);
    const common::LocalMapData d = to_local_map_data(map, 3, true, {5.5});
    EXPECT_EQ(d.id, 7u);
    EXPECT_EQ(d.revision, 3u);
    EXPECT_TRUE(d.finished);
    EXPECT_EQ(d.voxels.size(), map.voxels().size());
    // Grid frame = the odometry's map frame: p_odom = T_odom_anchor * T_anchor_grid * p_grid.
    const Eigen::Isometry3d T_odom_grid = d.T_odom_anchor * d.T_anchor_grid;
    EXPECT_LT((T_odom_grid.translation() - map.origin()).norm(), 1e-9);
    EXPECT_LT(rot_deg(T_odom_grid), 1e-9);
    for (std::size_t i = 0; i < d.voxels.size(); ++i) {
        const common::VoxelData& v = d.voxels[i];
        EXPECT_EQ(v.index, (v.centre.array() / 1.0f).floor().cast<int>().matrix());
        EXPECT_EQ(v.life.created, 5.5);
        EXPECT_EQ(v.life.observations, 1u);
    }
    odometry::Keyframe k;
    k.id = 4;
    k.stamp = 6.0;
    k.local_map_id = 7;
    k.T_odom_lidar = test::xy_yaw(5, 0, 60);
    k.points = {Eigen::Vector3f(1, 2, 3)};
    const common::KeyframeData kd = to_keyframe_data(k, anchor, 42);
    EXPECT_EQ(kd.scan_index, 42u);
    EXPECT_EQ(kd.local_map_id, 7u);
    EXPECT_TRUE((anchor * kd.T_anchor_lidar).isApprox(k.T_odom_lidar, 1e-12));
    EXPECT_EQ(kd.points, k.points);
}

}  // namespace
}  // namespace ltm::mapping
