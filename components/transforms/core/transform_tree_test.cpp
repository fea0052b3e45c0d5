#include "transforms/core/transform_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "common/core/pose_xyz_rpy.hpp"

namespace ltm::transforms {
namespace {

Eigen::Isometry3d pose(double x, double y, double z, double yaw_deg) {
    return common::pose_from_xyz_rpy({x, y, z, 0.0, 0.0, yaw_deg});
}

TEST(TransformTree, TheChainGivesTheLidarPoseInTheMap) {
    const Eigen::Isometry3d T_base_lidar =
        common::pose_from_xyz_rpy({0.3, 0.0, 1.2, 0.0, 2.0, 180.0});
    TransformTree tree(FrameNames{}, T_base_lidar);
    const Transform s = tree.static_transform();
    EXPECT_EQ(s.parent, "base_link");
    EXPECT_EQ(s.child, "lidar");
    EXPECT_TRUE(s.T_parent_child.isApprox(T_base_lidar));

    std::string problem;
    const Eigen::Isometry3d T_odom_lidar = pose(5.0, -1.0, 0.2, 30.0);
    auto first = tree.on_odometry(10.0, "odom", "lidar", T_odom_lidar, &problem);
    ASSERT_EQ(first.size(), 1u) << problem;  // no map -> odom yet
    EXPECT_EQ(first[0].parent, "odom");
    EXPECT_EQ(first[0].child, "base_link");
    EXPECT_TRUE((first[0].T_parent_child * T_base_lidar).isApprox(T_odom_lidar));

    const Eigen::Isometry3d T_map_odom = pose(100.0, 50.0, 0.0, -45.0);
    ASSERT_TRUE(tree.on_map_to_odom(10.05, "map", "odom", T_map_odom, &problem)) << problem;
    auto next = tree.on_odometry(10.1, "odom", "lidar", T_odom_lidar, &problem);
    ASSERT_EQ(next.size(), 2u);
    EXPECT_EQ(next[0].parent, "map");
    EXPECT_DOUBLE_EQ(next[0].stamp, 10.1);  // the latest correction, at the odometry's stamp
    const Eigen::Isometry3d T_map_lidar =
        next[0].T_parent_child * next[1].T_parent_child * s.T_parent_child;
    EXPECT_TRUE(T_map_lidar.isApprox(T_map_odom * T_odom_lidar, 1e-12));
}

TEST(TransformTree, ForeignFramesAndNonFinitePosesAreRefused) {
    TransformTree tree(FrameNames{}, Eigen::Isometry3d::Identity());
    std::string problem;
    EXPECT_TRUE(
        tree.on_odometry(1.0, "world", "lidar", Eigen::Isometry3d::Identity(), &problem).empty());
    EXPECT_NE(problem.find("'world'"), std::string::npos);
    Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
    bad.translation().x() = NAN;
    EXPECT_TRUE(tree.on_odometry(1.0, "odom", "lidar", bad, &problem).empty());
    EXPECT_FALSE(tree.on_map_to_odom(1.0, "map", "odom2", Eigen::Isometry3d::Identity(), &problem));
    EXPECT_FALSE(tree.has_map());
}

}  // namespace
}  // namespace ltm::transforms
