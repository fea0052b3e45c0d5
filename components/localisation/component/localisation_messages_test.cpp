#include "localisation/component/localisation_messages.hpp"

#include <gtest/gtest.h>

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::localisation {
namespace {

msg::PoseWithCovarianceStamped initial_pose(double var_x, double var_y) {
    msg::PoseWithCovarianceStamped m{};
    m.pose.pose.position = {3.0, -2.0, 0.0};
    m.pose.pose.orientation = {0.0, 0.0, std::sin(0.25), std::cos(0.25)};  // yaw 0.5 rad
    m.pose.covariance[0] = var_x;
    m.pose.covariance[7] = var_y;
    return m;
}

TEST(LocalisationMessages, InitialPoseRadiusIsThreeSigmaOfTheLargerVarianceAtLeastTwoMetres) {
    const PoseHint h = hint_from_msg(initial_pose(1.0, 4.0));  // sigma 2 m
    EXPECT_DOUBLE_EQ(h.radius, 6.0);
    EXPECT_TRUE(h.T_map_lidar.translation().isApprox(Eigen::Vector3d(3.0, -2.0, 0.0)));
    EXPECT_NEAR(Eigen::AngleAxisd(h.T_map_lidar.linear()).angle(), 0.5, 1e-12);
    // RViz's default (0.25 m^2: 1.5 m), none, or nonsense: the floor.
    EXPECT_DOUBLE_EQ(hint_from_msg(initial_pose(0.25, 0.25)).radius, 2.0);
    EXPECT_DOUBLE_EQ(hint_from_msg(initial_pose(0.0, 0.0)).radius, 2.0);
    EXPECT_DOUBLE_EQ(hint_from_msg(initial_pose(-1.0, NAN)).radius, 2.0);
    EXPECT_DOUBLE_EQ(hint_from_msg(initial_pose(4.0, 0.0), {2.0, 5.0}).radius, 5.0);
}

TEST(LocalisationMessages, StatusAndPoseCarryTheUpdate) {
    LocalisationUpdate u;
    u.stamp = 12.25;
    u.state = LocalisationState::kOffMap;
    u.pose_valid = true;
    u.T_map_lidar.translation() = Eigen::Vector3d(1, 2, 3);
    u.covariance = registration::Matrix6d::Identity();
    u.covariance(0, 5) = u.covariance(5, 0) = 0.5;  // x with rz
    u.confidence = 0.75;
    u.inlier_fraction = 0.5;
    u.global_ran = true;
    u.global_time_s = 0.3;
    u.lost_for = 1.5;
    u.since_fix = 20.0;
    u.message = "beyond the map";
    const auto s = status_msg(u, StatusCounters{4, 7}, "map");
    EXPECT_EQ(s->state, ltm_msgs_msg_LocalisationStatus_Constants_OFF_MAP);
    EXPECT_TRUE(s->pose_valid);
    EXPECT_TRUE(s->global_ran);
    EXPECT_FLOAT_EQ(s->confidence, 0.75f);
    EXPECT_DOUBLE_EQ(s->since_fix, 20.0);
    EXPECT_EQ(s->relocalisations, 4u);
    EXPECT_EQ(s->skipped_scans, 7u);
    EXPECT_EQ(convert::to_string(s->message), "beyond the map");
    EXPECT_EQ(convert::to_string(s->header.frame_id), "map");
    EXPECT_DOUBLE_EQ(convert::to_seconds(s->header.stamp), 12.25);

    const auto p = pose_msg(u, "map");
    EXPECT_DOUBLE_EQ(p->pose.pose.position.z, 3.0);
    EXPECT_DOUBLE_EQ(p->pose.covariance[5], 0.5);  // row-major (x y z rx ry rz), ROS's order
    EXPECT_DOUBLE_EQ(p->pose.covariance[30], 0.5);

    // No map: the reason, no pose, initialising.
    const auto none = status_msg(3.0, "no map to localise on: /x: not a directory", {}, "map");
    EXPECT_EQ(none->state, ltm_msgs_msg_LocalisationStatus_Constants_INITIALISING);
    EXPECT_FALSE(none->pose_valid);
    EXPECT_EQ(convert::to_string(none->message), "no map to localise on: /x: not a directory");
}

TEST(LocalisationMessages, EveryStateHasItsConstant) {
    EXPECT_EQ(to_msg_state(LocalisationState::kInitialising), 0);
    EXPECT_EQ(to_msg_state(LocalisationState::kTracking), 1);
    EXPECT_EQ(to_msg_state(LocalisationState::kLost), 2);
    EXPECT_EQ(to_msg_state(LocalisationState::kRelocalised), 3);
    EXPECT_EQ(to_msg_state(LocalisationState::kOffMap), 4);
}

}  // namespace
}  // namespace ltm::localisation
