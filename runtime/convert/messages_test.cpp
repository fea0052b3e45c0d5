// Every message builder of runtime/convert: build -> message (fields checked) -> back. The
// messages are owned: each is freed by its generated free function at the end of the test.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "runtime/convert/geometry.hpp"
#include "runtime/convert/imu.hpp"
#include "runtime/convert/loop_closure.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/path.hpp"
#include "runtime/convert/pose_graph.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/convert/transform.hpp"

using namespace ltm;
using namespace ltm::convert;

namespace {

Eigen::Isometry3d some_pose(double k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        Eigen::AngleAxisd(0.3 * k, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(k, -2 * k, 0.5 * k);
    return T;
}

Eigen::Matrix<double, 6, 6> some_matrix(double k) {
    Eigen::Matrix<double, 6, 6> m;
    for (int i = 0; i < 36; ++i) m(i / 6, i % 6) = k * 100 + i;
    return m;
}

msg::Time some_time() { return {1700000000, 123456789}; }  // not exact as a double

void expect_time(const msg::Time& a, const msg::Time& b) {
    EXPECT_EQ(a.sec, b.sec);
    EXPECT_EQ(a.nanosec, b.nanosec);
}

}  // namespace

TEST(StatusMessage, BuildAndBack) {
    StatusData in;
    in.stamp = some_time();
    in.frame_id = "odom";
    in.component = "robot/odometry";
    in.level = StatusLevel::kWarn;
    in.code = common::StatusCode::kRestarted;
    in.message = "scan 12: lost for 5 scans; a new segment";
    in.segment = 3;
    in.request_id = 7;
    const Owned<msg::Status> m = to_msg(in);
    EXPECT_EQ(m->level, ltm_msgs_msg_Status_Constants_WARN);
    EXPECT_STREQ(m->header.frame_id, "odom");
    EXPECT_STREQ(m->component, "robot/odometry");
    EXPECT_EQ(m->code, ltm_msgs_msg_Status_Constants_CODE_RESTARTED);
    EXPECT_STREQ(m->key, "restarted");
    EXPECT_EQ(m->segment, 3u);
    const StatusData out = from_msg(*m);
    expect_time(out.stamp, in.stamp);
    EXPECT_EQ(out.frame_id, in.frame_id);
    EXPECT_EQ(out.component, in.component);
    EXPECT_EQ(out.level, in.level);
    EXPECT_EQ(out.code, in.code);
    EXPECT_EQ(out.message, in.message);
    EXPECT_EQ(out.segment, 3u);
    EXPECT_EQ(out.request_id, 7u);
}

// Every code has its own text key, and the key reads back as the code.
TEST(StatusMessage, EveryCodeHasAKeyThatParsesBack) {
    std::set<std::string> keys;
    for (int v = 0; v <= common::kLastStatusCode; ++v) {
        const common::StatusCode c = common::status_code_from_wire(std::uint8_t(v));
        EXPECT_EQ(int(c), v);
        const std::string key = common::to_string(c);
        EXPECT_TRUE(keys.insert(key).second) << key;
        EXPECT_EQ(common::parse_status_code(key), c);
    }
    EXPECT_FALSE(common::parse_status_code("no_such_code").has_value());
    // A newer sender's code this build does not know.
    EXPECT_EQ(common::status_code_from_wire(common::kLastStatusCode + 1),
              common::StatusCode::kUnknown);
}

TEST(StatusMessage, ZeroedMessageReadsAsEmpty) {
    const msg::Status zero{};
    const StatusData s = from_msg(zero);
    EXPECT_EQ(s.component, "");
    EXPECT_EQ(s.level, StatusLevel::kOk);
    EXPECT_EQ(s.code, common::StatusCode::kUnknown);
    EXPECT_EQ(s.message, "");
}

TEST(TransformMessage, BuildAndBack) {
    TransformData in;
    in.stamp = some_time();
    in.parent_frame_id = "map";
    in.child_frame_id = "odom";
    in.T_parent_child = some_pose(2);
    const Owned<msg::TransformStamped> m = to_msg(in);
    EXPECT_STREQ(m->header.frame_id, "map");
    EXPECT_STREQ(m->child_frame_id, "odom");
    EXPECT_DOUBLE_EQ(m->transform.translation.y, -4.0);
    const msg::Pose p = to_pose(in.T_parent_child);  // the same numbers as a pose
    EXPECT_EQ(m->transform.rotation.w, p.orientation.w);
    EXPECT_EQ(m->transform.rotation.x, p.orientation.x);
    const TransformData out = from_msg(*m);
    expect_time(out.stamp, in.stamp);
    EXPECT_EQ(out.parent_frame_id, "map");
    EXPECT_EQ(out.child_frame_id, "odom");
    EXPECT_TRUE(out.T_parent_child.isApprox(in.T_parent_child, 1e-12));
}

TEST(PathMessage, PoseStampedBuildAndBack) {
    common::StampedPose in;
    in.stamp = 12.25;
    in.pose = some_pose(1);
    const Owned<msg::PoseStamped> m = to_msg(in, "world");
    EXPECT_STREQ(m->header.frame_id, "world");
    EXPECT_EQ(m->header.stamp.sec, 12);
    EXPECT_EQ(m->header.stamp.nanosec, 250000000u);
    const common::StampedPose out = from_msg(*m);
    EXPECT_EQ(out.stamp, 12.25);
    EXPECT_TRUE(out.pose.isApprox(in.pose, 1e-12));
}

TEST(PathMessage, PathBuildAndBack) {
    common::Trajectory in;
    for (int i = 0; i < 5; ++i) {
        common::StampedPose p;
        p.stamp = 100.5 + i;
        p.pose = some_pose(i);
        in.push_back(p);
    }
    const Owned<msg::Path> m = to_msg(in, "map");
    EXPECT_STREQ(m->header.frame_id, "map");
    EXPECT_EQ(m->header.stamp.sec, 0);  // a path without a stamp of its own
    ASSERT_EQ(m->poses._length, 5u);
    for (std::uint32_t i = 0; i < 5; ++i) EXPECT_STREQ(m->poses._buffer[i].header.frame_id, "map");
    const common::Trajectory out = from_msg(*m);
    ASSERT_EQ(out.size(), in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        EXPECT_EQ(out[i].stamp, in[i].stamp);
        EXPECT_TRUE(out[i].pose.isApprox(in[i].pose, 1e-12));
    }
    EXPECT_TRUE(from_msg(*to_msg(common::Trajectory{}, "map")).empty());
}

TEST(OdometryMessage, BuildAndBack) {
    OdometryData in;
    in.stamp = some_time();
    in.frame_id = "odom";
    in.child_frame_id = "lidar";
    in.T_parent_child = some_pose(3);
    in.pose_covariance = some_matrix(1);
    in.linear_velocity = {1, 2, 3};
    in.angular_velocity = {-0.1, 0.2, -0.3};
    in.twist_covariance = some_matrix(2);
    const Owned<msg::Odometry> m = to_msg(in);
    EXPECT_STREQ(m->header.frame_id, "odom");
    EXPECT_STREQ(m->child_frame_id, "lidar");
    EXPECT_EQ(m->pose.covariance[7], 107.0);  // row-major
    EXPECT_EQ(m->twist.twist.angular.z, -0.3);
    EXPECT_EQ(m->twist.covariance[35], 235.0);
    const OdometryData out = from_msg(*m);
    expect_time(out.stamp, in.stamp);
    EXPECT_EQ(out.frame_id, "odom");
    EXPECT_EQ(out.child_frame_id, "lidar");
    EXPECT_TRUE(out.T_parent_child.isApprox(in.T_parent_child, 1e-12));
    EXPECT_EQ(out.pose_covariance, in.pose_covariance);
    EXPECT_EQ(out.linear_velocity, in.linear_velocity);
    EXPECT_EQ(out.angular_velocity, in.angular_velocity);
    EXPECT_EQ(out.twist_covariance, in.twist_covariance);
}

TEST(ImuMessage, BuildAndBack) {
    ImuData in;
    in.stamp = 12.345;
    in.frame_id = "imu_link";
    in.angular_velocity = {0.1, -0.2, 1.5};
    in.linear_acceleration = {0.3, 0.0, 9.81};
    in.gyro_variance = 4e-4;
    in.accel_variance = 1e-3;
    const Owned<msg::Imu> m = to_msg(in);
    EXPECT_EQ(m->orientation_covariance[0], -1.0);  // no orientation
    EXPECT_EQ(m->angular_velocity_covariance[4], 4e-4);
    ImuData out;
    ASSERT_EQ(from_msg(*m, &out), "");
    EXPECT_NEAR(out.stamp, in.stamp, 1e-9);
    EXPECT_EQ(out.frame_id, "imu_link");
    EXPECT_TRUE(out.angular_velocity.isApprox(in.angular_velocity));
    EXPECT_TRUE(out.linear_acceleration.isApprox(in.linear_acceleration));
    EXPECT_EQ(out.accel_variance, 1e-3);
    ImuData bad = in;
    bad.angular_velocity.z() = std::nan("");
    EXPECT_EQ(from_msg(*to_msg(bad), &out), "IMU angular velocity is not finite");
}

TEST(OdometryMessage, ReparentMovesThePoseAndRotatesItsCovariance) {
    OdometryData in;
    in.frame_id = "odom";
    in.child_frame_id = "lidar";
    in.T_parent_child = some_pose(1);
    in.pose_covariance = Eigen::Matrix<double, 6, 6>::Zero();
    in.pose_covariance(0, 0) = 4.0;  // uncertain along odom's x only
    in.pose_covariance(5, 5) = 0.01;
    in.linear_velocity = {1, 0, 0};
    Eigen::Isometry3d T_map_odom = Eigen::Isometry3d::Identity();
    T_map_odom.linear() =
        Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T_map_odom.translation() = Eigen::Vector3d(10, 0, 0);
    const OdometryData out = reparent(in, T_map_odom, "map");
    EXPECT_EQ(out.frame_id, "map");
    EXPECT_EQ(out.child_frame_id, "lidar");
    EXPECT_TRUE(out.T_parent_child.isApprox(T_map_odom * in.T_parent_child, 1e-12));
    EXPECT_NEAR(out.pose_covariance(1, 1), 4.0, 1e-12);  // odom's x is map's y
    EXPECT_NEAR(out.pose_covariance(0, 0), 0.0, 1e-12);
    EXPECT_NEAR(out.pose_covariance(5, 5), 0.01, 1e-12);  // yaw about the same axis
    EXPECT_EQ(out.linear_velocity, in.linear_velocity);   // child frame: unchanged
}

TEST(PoseGraphMessage, BuildAndBack) {
    PoseGraphData in;
    in.frame_id = "map";
    in.revision = 7;
    for (std::uint64_t i = 0; i < 4; ++i) in.anchors.push_back({10 + i, some_pose(i)});
    in.edges.push_back({10, 11, GraphEdgeKind::kOdometry, some_pose(1), some_matrix(1)});
    in.edges.push_back({13, 10, GraphEdgeKind::kLoop, some_pose(2), some_matrix(2)});
    in.edges.push_back({12, 13, GraphEdgeKind::kSession, some_pose(3), some_matrix(3)});
    const Owned<msg::PoseGraph> m = to_msg(in);
    EXPECT_STREQ(m->header.frame_id, "map");
    EXPECT_EQ(m->revision, 7u);
    ASSERT_EQ(m->anchors._length, 4u);
    ASSERT_EQ(m->edges._length, 3u);
    EXPECT_EQ(m->anchors._buffer[3].id, 13u);
    EXPECT_EQ(m->edges._buffer[1].kind, ltm_msgs_msg_PoseGraphEdge_Constants_LOOP);
    EXPECT_EQ(m->edges._buffer[2].kind, ltm_msgs_msg_PoseGraphEdge_Constants_SESSION);
    EXPECT_EQ(m->edges._buffer[1].information[1], 201.0);
    const PoseGraphData out = from_msg(*m);
    EXPECT_EQ(out.frame_id, "map");
    EXPECT_EQ(out.revision, 7u);
    ASSERT_EQ(out.anchors.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(out.anchors[i].local_map_id, in.anchors[i].local_map_id);
        EXPECT_TRUE(out.anchors[i].T_map_anchor.isApprox(in.anchors[i].T_map_anchor, 1e-12));
    }
    ASSERT_EQ(out.edges.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(out.edges[i].from_map_id, in.edges[i].from_map_id);
        EXPECT_EQ(out.edges[i].to_map_id, in.edges[i].to_map_id);
        EXPECT_EQ(out.edges[i].kind, in.edges[i].kind);
        EXPECT_TRUE(out.edges[i].T_from_to.isApprox(in.edges[i].T_from_to, 1e-12));
        EXPECT_EQ(out.edges[i].information, in.edges[i].information);
    }
}

TEST(PoseGraphMessage, EmptyGraph) {
    PoseGraphData in;
    const Owned<msg::PoseGraph> m = to_msg(in);
    EXPECT_STREQ(m->header.frame_id, "");
    EXPECT_EQ(m->anchors._buffer, nullptr);
    const PoseGraphData out = from_msg(*m);
    EXPECT_TRUE(out.anchors.empty());
    EXPECT_TRUE(out.edges.empty());
}

TEST(LoopClosureMessage, BuildAndBack) {
    LoopClosureData in;
    in.stamp = some_time();
    in.frame_id = "map";
    in.from_map_id = 3;
    in.to_map_id = 41;
    in.from_keyframe_id = 30;
    in.to_keyframe_id = 410;
    in.T_from_to = some_pose(4);
    in.information = some_matrix(4);
    in.score = 0.25f;
    in.fitness = 0.8f;
    in.residual = 0.05f;
    in.accepted = true;
    const Owned<msg::LoopClosure> m = to_msg(in);
    EXPECT_STREQ(m->header.frame_id, "map");
    EXPECT_EQ(m->to_keyframe_id, 410u);
    EXPECT_EQ(m->information[35], 435.0);
    const LoopClosureData out = from_msg(*m);
    expect_time(out.stamp, in.stamp);
    EXPECT_EQ(out.frame_id, "map");
    EXPECT_EQ(out.from_map_id, 3u);
    EXPECT_EQ(out.to_map_id, 41u);
    EXPECT_EQ(out.from_keyframe_id, 30u);
    EXPECT_EQ(out.to_keyframe_id, 410u);
    EXPECT_TRUE(out.T_from_to.isApprox(in.T_from_to, 1e-12));
    EXPECT_EQ(out.information, in.information);
    EXPECT_EQ(out.score, 0.25f);
    EXPECT_EQ(out.fitness, 0.8f);
    EXPECT_EQ(out.residual, 0.05f);
    EXPECT_TRUE(out.accepted);
}
