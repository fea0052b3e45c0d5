#include "odometry/core/local_map_export.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

double rot_deg(const Eigen::Isometry3d& T) {
    return Eigen::AngleAxisd(T.linear()).angle() * 180.0 / M_PI;
}

TEST(LocalMapExport, LocalMapAndKeyframeConversions) {
    const registration::test::Scene scene = registration::test::room_scene();
    const Eigen::Isometry3d anchor = registration::test::make_pose(3.3, -1.2, 1.5, 0, 0, 50);
    LocalMap map(7, anchor, 1.0, 30.0, VoxelConfig(), 5.0);
    const common::PointCloud scan =
        registration::test::scan_scene(scene, registration::test::ScanPattern(), anchor, anchor, 3);
    const Eigen::Vector3f sensor = (anchor.translation() - map.origin()).cast<float>();
    std::vector<Eigen::Vector3f> pts;
    for (const Eigen::Vector3f& p : scan.points)
        pts.push_back((anchor * p.cast<double>() - map.origin()).cast<float>());
    map.integrate(pts, sensor, 5.5);
    const common::LocalMapData d = to_local_map_data(map, 3, true, {5.5});
    EXPECT_EQ(d.id, 7u);
    EXPECT_EQ(d.revision, 3u);
    EXPECT_TRUE(d.finished);
    ASSERT_GT(d.voxels.size(), 500u);
    EXPECT_EQ(d.voxels.size(), map.voxels().size());
    EXPECT_EQ(d.observation_times, std::vector<double>{5.5});
    // Grid frame = the odometry's map frame: p_odom = T_odom_anchor * T_anchor_grid * p_grid.
    const Eigen::Isometry3d T_odom_grid = d.T_odom_anchor * d.T_anchor_grid;
    EXPECT_LT((T_odom_grid.translation() - map.origin()).norm(), 1e-9);
    EXPECT_LT(rot_deg(T_odom_grid), 1e-9);
    for (const common::VoxelData& v : d.voxels) {
        EXPECT_EQ(v.index, (v.centre.array() / 1.0f).floor().cast<int>().matrix());
        EXPECT_EQ(v.life.created, 5.5);
        EXPECT_EQ(v.life.observations, 1u);
    }
    Keyframe k;
    k.id = 4;
    k.stamp = 6.0;
    k.local_map_id = 7;
    k.T_odom_lidar = registration::test::make_pose(5, 0, 0, 0, 0, 60);
    k.points = {Eigen::Vector3f(1, 2, 3)};
    const common::KeyframeData kd = to_keyframe_data(k, anchor, 42);
    EXPECT_EQ(kd.scan_index, 42u);
    EXPECT_EQ(kd.local_map_id, 7u);
    EXPECT_TRUE((anchor * kd.T_anchor_lidar).isApprox(k.T_odom_lidar, 1e-12));
    EXPECT_EQ(kd.points, k.points);
}

}  // namespace
}  // namespace ltm::odometry
