// Where a new site's map pose comes from (core/new_site_pose.hpp).
#include "localisation/core/new_site_pose.hpp"

#include <gtest/gtest.h>

namespace ltm::localisation {
namespace {

OdometryPose at(double stamp, double x) {
    OdometryPose o;
    o.stamp = stamp;
    o.T_odom_lidar.translation() = Eigen::Vector3d(x, 0, 0);
    return o;
}

Eigen::Isometry3d shifted(double y) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0, y, 0);
    return T;
}

TEST(NewSitePose, NamesParseAndOthersAreRefused) {
    EXPECT_EQ(parse_new_site_pose("slam_map_to_odom"), NewSitePoseSource::kSlamMapToOdom);
    EXPECT_EQ(parse_new_site_pose("slam_odometry"), NewSitePoseSource::kSlamOdometry);
    EXPECT_EQ(parse_new_site_pose("odometry"), NewSitePoseSource::kBaseStation);
    EXPECT_FALSE(parse_new_site_pose("slam"));
}

// The composed mode: poses before the first map_to_odom wait for it (none lost), then every pose
// goes out at once under the newest map_to_odom (the mapping's thread is never waited for).
TEST(NewSitePose, PosesWaitForTheFirstMapToOdomThenGoOutAtOnce) {
    NewSitePose n(NewSitePoseSource::kSlamMapToOdom);
    EXPECT_FALSE(n.odometry(at(0.0, 0.0)));
    EXPECT_FALSE(n.odometry(at(0.1, 1.0)));
    const std::vector<LocalisationUpdate> flushed = n.map_to_odom(shifted(2.0));
    ASSERT_EQ(flushed.size(), 2u);
    EXPECT_DOUBLE_EQ(flushed[0].stamp, 0.0);
    EXPECT_TRUE(flushed[1].pose_valid);
    EXPECT_TRUE(flushed[1].T_map_lidar.translation().isApprox(Eigen::Vector3d(1, 2, 0)));
    EXPECT_EQ(flushed[1].state, LocalisationState::kOffMap);

    const auto u = n.odometry(at(0.2, 3.0));
    ASSERT_TRUE(u);
    EXPECT_TRUE(u->T_map_lidar.translation().isApprox(Eigen::Vector3d(3, 2, 0)));
    EXPECT_TRUE(n.map_to_odom(shifted(-1.0)).empty());  // nothing waits any more
    EXPECT_TRUE(
        n.odometry(at(0.3, 3.0))->T_map_lidar.translation().isApprox(Eigen::Vector3d(3, -1, 0)));
    EXPECT_TRUE(n.frame_is_ours());
}

TEST(NewSitePose, WaitingIsBounded) {
    NewSitePose n(NewSitePoseSource::kSlamMapToOdom);
    for (std::size_t i = 0; i < NewSitePose::kMaxWaiting + 5; ++i)
        EXPECT_FALSE(n.odometry(at(0.1 * static_cast<double>(i), 0.0)));
    EXPECT_EQ(n.dropped(), 5u);
    const std::vector<LocalisationUpdate> flushed = n.map_to_odom(shifted(0.0));
    ASSERT_EQ(flushed.size(), NewSitePose::kMaxWaiting);
    EXPECT_NEAR(flushed.front().stamp, 0.5, 1e-9);  // the oldest went
}

// The split robot: no pose until the base station says its map_to_odom is of no version (a new
// site there too), and none once a version is on its way.
TEST(NewSitePose, TheBaseStationsFrameIsUsedOnlyWhenItIsThisSessions) {
    NewSitePose n(NewSitePoseSource::kBaseStation);
    n.map_to_odom(shifted(1.0));
    auto u = n.odometry(at(0.0, 0.0));
    ASSERT_TRUE(u);
    EXPECT_FALSE(u->pose_valid);  // which version is it of? not said yet
    n.base_version("v0002");
    EXPECT_FALSE(n.frame_is_ours());
    EXPECT_FALSE(n.odometry(at(0.1, 0.0))->pose_valid);
    n.base_version("");
    EXPECT_TRUE(n.frame_is_ours());
    u = n.odometry(at(0.2, 0.0));
    ASSERT_TRUE(u->pose_valid);
    EXPECT_TRUE(u->T_map_lidar.translation().isApprox(Eigen::Vector3d(0, 1, 0)));
    n.offered();
    EXPECT_FALSE(n.odometry(at(0.3, 0.0))->pose_valid);
}

TEST(NewSitePose, TheSlamPoseIsTheMapPose) {
    NewSitePose n(NewSitePoseSource::kSlamOdometry);
    EXPECT_FALSE(n.composes_odometry());
    EXPECT_FALSE(n.odometry(at(0.0, 0.0)));
    const LocalisationUpdate u =
        NewSitePose::slam_pose(1.5, shifted(4.0), registration::Matrix6d::Identity());
    EXPECT_TRUE(u.pose_valid);
    EXPECT_EQ(u.state, LocalisationState::kOffMap);
}

}  // namespace
}  // namespace ltm::localisation
