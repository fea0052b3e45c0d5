// Every message type survives a trip through Cyclone DDS (serialise, deliver, deserialise).
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/convert/loop_closure.hpp"
#include "runtime/convert/odometry.hpp"
#include "runtime/convert/path.hpp"
#include "runtime/convert/pointcloud2.hpp"
#include "runtime/convert/pose_graph.hpp"
#include "runtime/convert/status.hpp"
#include "runtime/convert/transform.hpp"
#include "runtime/messages.hpp"
#include "runtime/testing/dds_loopback.hpp"

using namespace ltm;

namespace {

class Dds : public ::testing::Test {
  protected:
    // Writes `in` and hands the received sample to `check`.
    template <class T>
    void roundtrip(const T& in, const std::function<void(const T&)>& check) {
        static runtime::testing::DdsLoopback dds(212);
        dds.roundtrip(in, check);
    }
};

Eigen::Isometry3d some_pose(double k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        Eigen::AngleAxisd(0.3 * k, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(k, -2 * k, 0.5 * k);
    return T;
}

// A view of `s` for hand-filled messages (borrowed: these are never freed through the message).
char* c(std::string& s) { return convert::borrow_string(s); }

}  // namespace

TEST_F(Dds, PointCloud2ThroughTheConverter) {
    common::PointCloud cloud;
    for (int i = 0; i < 1000; ++i) {
        cloud.points.emplace_back(i * 0.1f, -i * 0.2f, 1.5f);
        cloud.intensity.push_back(i % 7);
        cloud.time.push_back(i * 1e-4f);
    }
    cloud.stamp = 1234.5678;
    cloud.frame_id = "velodyne";
    convert::PointCloud2Builder builder;
    roundtrip<msg::PointCloud2>(builder.build(cloud), [&](const msg::PointCloud2& m) {
        common::PointCloud back;
        ASSERT_EQ(convert::from_pointcloud2(m, back), "");
        EXPECT_EQ(back.points, cloud.points);
        EXPECT_EQ(back.intensity, cloud.intensity);
        EXPECT_EQ(back.time, cloud.time);
        EXPECT_NEAR(back.stamp, cloud.stamp, 1e-9);
        EXPECT_EQ(back.frame_id, "velodyne");
    });
}

TEST_F(Dds, OdometryAndPath) {
    std::string odom = "odom", child = "lidar";
    msg::Odometry o{};
    o.header.stamp = convert::to_time(10.25);
    o.header.frame_id = c(odom);
    o.child_frame_id = c(child);
    o.pose.pose = convert::to_pose(some_pose(1));
    for (int i = 0; i < 36; ++i) o.pose.covariance[i] = i, o.twist.covariance[i] = -i;
    o.twist.twist.linear = {1, 2, 3};
    roundtrip<msg::Odometry>(o, [&](const msg::Odometry& r) {
        EXPECT_EQ(std::string(r.child_frame_id), "lidar");
        EXPECT_TRUE(convert::to_isometry(r.pose.pose).isApprox(some_pose(1), 1e-12));
        EXPECT_EQ(r.pose.covariance[35], 35);
        EXPECT_EQ(r.twist.covariance[7], -7);
        EXPECT_EQ(r.twist.twist.linear.z, 3);
        EXPECT_EQ(r.header.stamp.nanosec, 250000000u);
    });
    std::vector<msg::PoseStamped> poses(5);
    for (int i = 0; i < 5; ++i) {
        poses[i].header.frame_id = c(odom);
        poses[i].pose = convert::to_pose(some_pose(i));
    }
    msg::Path p{};
    p.header.frame_id = c(odom);
    p.poses._buffer = poses.data();
    p.poses._length = p.poses._maximum = 5;
    roundtrip<msg::Path>(p, [&](const msg::Path& r) {
        ASSERT_EQ(r.poses._length, 5u);
        EXPECT_TRUE(convert::to_isometry(r.poses._buffer[4].pose).isApprox(some_pose(4), 1e-12));
    });
}

TEST_F(Dds, LocalMapWithVoxelsAndLifeRecords) {
    std::string frame = "odom";
    std::vector<msg::Voxel> voxels(3);
    std::vector<std::uint16_t> seen = {0, 2};
    std::vector<double> times = {1.0, 1.1, 1.2};
    for (int i = 0; i < 3; ++i) {
        voxels[i].ix = i;
        voxels[i].iy = -i;
        voxels[i].iz = 7;
        voxels[i].centre[0] = 0.25f * i;
        voxels[i].normal[2] = 1;
        voxels[i].point_count = 10 + i;
        voxels[i].stability = 0.9f;
        voxels[i].life.created = 1.0;
        voxels[i].life.last_seen = 1.2;
        voxels[i].life.observations = 2;
        voxels[i].life.seen._buffer = seen.data();
        voxels[i].life.seen._length = voxels[i].life.seen._maximum = 2;
    }
    msg::LocalMap m{};
    m.header.frame_id = c(frame);
    m.id = 42;
    m.revision = 3;
    m.finished = true;
    m.anchor = convert::to_pose(some_pose(2));
    m.bbox_min = {-20, -20, -5};
    m.bbox_max = {20, 20, 5};
    m.voxel_size = 0.5f;
    m.observation_times._buffer = times.data();
    m.observation_times._length = m.observation_times._maximum = 3;
    m.voxels._buffer = voxels.data();
    m.voxels._length = m.voxels._maximum = 3;
    roundtrip<msg::LocalMap>(m, [&](const msg::LocalMap& r) {
        EXPECT_EQ(r.id, 42u);
        EXPECT_TRUE(r.finished);
        ASSERT_EQ(r.voxels._length, 3u);
        EXPECT_EQ(r.voxels._buffer[2].iy, -2);
        EXPECT_EQ(r.voxels._buffer[2].centre[0], 0.5f);
        EXPECT_EQ(r.voxels._buffer[1].point_count, 11u);
        ASSERT_EQ(r.voxels._buffer[1].life.seen._length, 2u);
        EXPECT_EQ(r.voxels._buffer[1].life.seen._buffer[1], 2);
        EXPECT_EQ(r.observation_times._buffer[2], 1.2);
        EXPECT_EQ(r.bbox_max.z, 5);
    });
}

TEST_F(Dds, LocalMapDataAndKeyframeDataThroughTheConverters) {
    common::LocalMapData d;
    d.id = 5;
    d.revision = 2;
    d.finished = true;
    d.segment = 2;
    d.T_odom_anchor = some_pose(1.5);
    d.T_anchor_grid = some_pose(-0.5);
    d.bbox_min = {-50, -50, -10};
    d.bbox_max = {50, 50, 10};
    d.voxel_size = 0.75f;
    d.observation_times = {3.0, 3.1};
    for (int i = 0; i < 100; ++i) {
        common::VoxelData v;
        v.index = {i, -i, i % 3};
        v.centre = {0.1f * i, 0.2f, -0.3f};
        v.normal = {0, 0, 1};
        v.point_count = i;
        v.planarity = 0.8f;
        v.stability = 0.95f;
        v.life.created = 3.0;
        v.life.last_seen = 3.1;
        v.life.observations = 2;
        v.life.health = 0.5f;
        v.life.seen = {0, 1};
        d.voxels.push_back(v);
    }
    convert::LocalMapBuilder builder;
    roundtrip<msg::LocalMap>(builder.build(d, 3.1, "odom"), [&](const msg::LocalMap& m) {
        const common::LocalMapData r = convert::from_msg(m);
        EXPECT_EQ(r.id, 5u);
        EXPECT_TRUE(r.finished);
        EXPECT_EQ(r.segment, 2u);
        EXPECT_TRUE(r.T_odom_anchor.isApprox(d.T_odom_anchor, 1e-12));
        EXPECT_TRUE(r.T_anchor_grid.isApprox(d.T_anchor_grid, 1e-12));
        EXPECT_EQ(r.bbox_max, d.bbox_max);
        EXPECT_EQ(r.observation_times, d.observation_times);
        ASSERT_EQ(r.voxels.size(), 100u);
        EXPECT_EQ(r.voxels[42].index, d.voxels[42].index);
        EXPECT_EQ(r.voxels[42].centre, d.voxels[42].centre);
        EXPECT_EQ(r.voxels[42].life.seen, d.voxels[42].life.seen);
        EXPECT_EQ(r.voxels[42].life.health, 0.5f);
    });
    common::KeyframeData k;
    k.id = 3;
    k.scan_index = 30;
    k.local_map_id = 5;
    k.segment = 1;
    k.stamp = 3.05;
    k.T_odom_lidar = some_pose(2);
    k.T_anchor_lidar = some_pose(0.2);
    k.points = {{1, 2, 3}, {4, 5, 6}};
    convert::KeyframeBuilder kb;
    roundtrip<msg::Keyframe>(kb.build(k, "odom", "lidar"), [&](const msg::Keyframe& m) {
        const common::KeyframeData r = convert::from_msg(m);
        EXPECT_EQ(r.scan_index, 30u);
        EXPECT_EQ(r.segment, std::optional<std::uint32_t>(1));
        EXPECT_NEAR(r.stamp, 3.05, 1e-9);
        EXPECT_TRUE(r.T_anchor_lidar.isApprox(k.T_anchor_lidar, 1e-12));
        EXPECT_EQ(r.points, k.points);
    });
}

TEST_F(Dds, KeyframeGraphLoopStatusChangesMesh) {
    std::string frame = "map", comp = "odometry", code = "skip", text = "empty scan";
    std::vector<float> values(20 * 60, 1.5f), spreads(20 * 60, 0.5f);
    std::vector<std::uint8_t> occupied(20 * 60, 1);
    msg::Keyframe k{};
    k.header.frame_id = c(frame);
    k.points.header.frame_id = c(frame);
    k.id = 7;
    k.local_map_id = 2;
    k.descriptor.kind = 1;
    k.descriptor.rings = 20;
    k.descriptor.sectors = 60;
    k.descriptor.values._buffer = values.data();
    k.descriptor.values._length = k.descriptor.values._maximum = values.size();
    k.descriptor.spreads._buffer = spreads.data();
    k.descriptor.spreads._length = k.descriptor.spreads._maximum = spreads.size();
    k.descriptor.occupied._buffer = occupied.data();
    k.descriptor.occupied._length = k.descriptor.occupied._maximum = occupied.size();
    k.descriptor.sensor_height = 1.73f;
    k.segment = 4;
    roundtrip<msg::Keyframe>(k, [&](const msg::Keyframe& r) {
        EXPECT_EQ(r.descriptor.values._length, 1200u);
        EXPECT_EQ(r.descriptor.spreads._buffer[19], 0.5f);
        EXPECT_EQ(r.descriptor.occupied._buffer[1199], 1);
        EXPECT_EQ(r.descriptor.sensor_height, 1.73f);
        EXPECT_EQ(r.localisation_descriptor.rings, 0);
        EXPECT_EQ(r.local_map_id, 2u);
        EXPECT_EQ(r.segment, 4u);
    });

    std::vector<msg::AnchorPose> anchors(2);
    anchors[1].id = 9;
    anchors[1].pose = convert::to_pose(some_pose(3));
    std::vector<msg::PoseGraphEdge> edges(1);
    edges[0].from_id = 0;
    edges[0].to_id = 9;
    edges[0].kind = 1;
    edges[0].information[0] = 100;
    msg::PoseGraph g{};
    g.header.frame_id = c(frame);
    g.revision = 5;
    g.anchors._buffer = anchors.data();
    g.anchors._length = g.anchors._maximum = 2;
    g.edges._buffer = edges.data();
    g.edges._length = g.edges._maximum = 1;
    roundtrip<msg::PoseGraph>(g, [&](const msg::PoseGraph& r) {
        EXPECT_EQ(r.revision, 5u);
        EXPECT_TRUE(convert::to_isometry(r.anchors._buffer[1].pose).isApprox(some_pose(3), 1e-12));
        EXPECT_EQ(r.edges._buffer[0].information[0], 100);
        EXPECT_EQ(r.edges._buffer[0].kind, ltm_msgs_msg_PoseGraphEdge_Constants_LOOP);
    });

    msg::LoopClosure l{};
    l.header.frame_id = c(frame);
    l.from_map_id = 1;
    l.to_map_id = 30;
    l.relative_pose = convert::to_pose(some_pose(0.5));
    l.score = 0.12f;
    l.accepted = true;
    roundtrip<msg::LoopClosure>(l, [&](const msg::LoopClosure& r) {
        EXPECT_EQ(r.to_map_id, 30u);
        EXPECT_FLOAT_EQ(r.score, 0.12f);
        EXPECT_TRUE(r.accepted);
    });

    msg::LocalisationStatus s{};
    s.header.frame_id = c(frame);
    s.state = ltm_msgs_msg_LocalisationStatus_Constants_RELOCALISED;
    s.message = c(text);
    s.inlier_fraction = 0.75f;
    s.pose_valid = true;
    s.since_fix = 12.5;
    s.skipped_scans = 4;
    roundtrip<msg::LocalisationStatus>(s, [&](const msg::LocalisationStatus& r) {
        EXPECT_EQ(r.state, 3);
        EXPECT_EQ(std::string(r.message), "empty scan");
        EXPECT_FLOAT_EQ(r.inlier_fraction, 0.75f);
        EXPECT_TRUE(r.pose_valid);
        EXPECT_DOUBLE_EQ(r.since_fix, 12.5);
        EXPECT_EQ(r.skipped_scans, 4u);
    });

    std::vector<float> voxels = {1, 2, 3, 4, 5, 6};
    std::vector<msg::SegmentChange> changes(1);
    changes[0].id = 4;
    changes[0].reason = ltm_msgs_msg_SegmentChange_Constants_VANISHED;
    changes[0].region[1] = -2;
    changes[0].voxels._buffer = voxels.data();
    changes[0].voxels._length = changes[0].voxels._maximum = 6;
    msg::MapChangeSet cs{};
    cs.header.frame_id = c(frame);
    cs.voxel_size = 0.25f;
    cs.changes._buffer = changes.data();
    cs.changes._length = cs.changes._maximum = 1;
    roundtrip<msg::MapChangeSet>(cs, [&](const msg::MapChangeSet& r) {
        ASSERT_EQ(r.changes._length, 1u);
        EXPECT_EQ(r.changes._buffer[0].reason, ltm_msgs_msg_SegmentChange_Constants_VANISHED);
        EXPECT_EQ(r.changes._buffer[0].region[1], -2);
        EXPECT_EQ(r.changes._buffer[0].voxels._buffer[5], 6.0f);
        EXPECT_EQ(r.voxel_size, 0.25f);
    });

    std::vector<float> vertices = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<std::uint32_t> tris = {0, 1, 2};
    msg::Mesh mesh{};
    mesh.header.frame_id = c(frame);
    mesh.local_map_id = 11;
    mesh.vertices._buffer = vertices.data();
    mesh.vertices._length = mesh.vertices._maximum = vertices.size();
    mesh.triangles._buffer = tris.data();
    mesh.triangles._length = mesh.triangles._maximum = tris.size();
    roundtrip<msg::Mesh>(mesh, [&](const msg::Mesh& r) {
        EXPECT_EQ(r.vertices._length, 9u);
        EXPECT_EQ(r.triangles._buffer[2], 2u);
    });

    msg::Status st{};
    st.header.frame_id = c(frame);
    st.component = c(comp);
    st.code = ltm_msgs_msg_Status_Constants_CODE_SKIPPED;
    st.key = c(code);
    st.message = c(text);
    st.level = ltm_msgs_msg_Status_Constants_WARN;
    st.segment = 5;
    st.request_id = 0xfffffffeu;
    roundtrip<msg::Status>(st, [&](const msg::Status& r) {
        EXPECT_EQ(r.code, ltm_msgs_msg_Status_Constants_CODE_SKIPPED);
        EXPECT_EQ(std::string(r.key), "skip");
        EXPECT_EQ(r.level, 1);
        EXPECT_EQ(r.segment, 5u);
        EXPECT_EQ(r.request_id, 0xfffffffeu);
    });

    std::string dir = "/tmp/map", ply = "";
    msg::MapRequest req{};
    req.id = 7;
    req.command = ltm_msgs_msg_MapRequest_Constants_SAVE_ALL;
    req.map_dir = c(dir);
    req.global_map_file = c(ply);
    roundtrip<msg::MapRequest>(req, [&](const msg::MapRequest& r) {
        EXPECT_EQ(r.id, 7u);
        EXPECT_EQ(r.command, 2);
        EXPECT_EQ(std::string(r.map_dir), "/tmp/map");
        EXPECT_EQ(std::string(r.global_map_file), "");
    });
}

TEST_F(Dds, TransformAndPoseWithCovariance) {
    std::string a = "map", b = "odom";
    msg::TransformStamped t{};
    t.header.frame_id = c(a);
    t.child_frame_id = c(b);
    t.transform.translation = {1, 2, 3};
    t.transform.rotation = {0, 0, 0, 1};
    roundtrip<msg::TransformStamped>(t, [&](const msg::TransformStamped& r) {
        EXPECT_EQ(std::string(r.child_frame_id), "odom");
        EXPECT_EQ(r.transform.translation.y, 2);
        EXPECT_EQ(r.transform.rotation.w, 1);
    });
    msg::PoseWithCovarianceStamped p{};
    p.header.frame_id = c(a);
    p.pose.pose = convert::to_pose(some_pose(2));
    p.pose.covariance[14] = 0.01;
    roundtrip<msg::PoseWithCovarianceStamped>(p, [&](const msg::PoseWithCovarianceStamped& r) {
        EXPECT_EQ(r.pose.covariance[14], 0.01);
        EXPECT_TRUE(convert::to_isometry(r.pose.pose).isApprox(some_pose(2), 1e-12));
    });
}

// The owned messages of the builders go out through Cyclone and read back the same.
TEST_F(Dds, BuiltMessagesThroughDds) {
    const msg::Time stamp{1700000000, 123456789};
    convert::StatusData st{stamp,
                           "odom",
                           "robot/odometry",
                           convert::StatusLevel::kError,
                           common::StatusCode::kRestarted,
                           "scan 3: lost for 1 s",
                           4,
                           9};
    roundtrip<msg::Status>(*convert::to_msg(st), [&](const msg::Status& r) {
        const convert::StatusData o = convert::from_msg(r);
        EXPECT_EQ(o.stamp.nanosec, stamp.nanosec);
        EXPECT_EQ(o.component, st.component);
        EXPECT_EQ(o.level, st.level);
        EXPECT_EQ(o.code, st.code);
        EXPECT_STREQ(r.key, "restarted");
        EXPECT_EQ(o.message, st.message);
        EXPECT_EQ(o.segment, 4u);
        EXPECT_EQ(o.request_id, 9u);
    });
    convert::TransformData tf{stamp, "map", "odom", some_pose(2)};
    roundtrip<msg::TransformStamped>(*convert::to_msg(tf), [&](const msg::TransformStamped& r) {
        const convert::TransformData o = convert::from_msg(r);
        EXPECT_EQ(o.parent_frame_id, "map");
        EXPECT_EQ(o.child_frame_id, "odom");
        EXPECT_TRUE(o.T_parent_child.isApprox(tf.T_parent_child, 1e-12));
    });
    common::Trajectory path;
    for (int i = 0; i < 50; ++i) path.push_back({10.0 + 0.1 * i, some_pose(i)});
    roundtrip<msg::Path>(*convert::to_msg(path, "map"), [&](const msg::Path& r) {
        const common::Trajectory o = convert::from_msg(r);
        ASSERT_EQ(o.size(), path.size());
        EXPECT_EQ(convert::to_string(r.poses._buffer[49].header.frame_id), "map");
        EXPECT_TRUE(o[49].pose.isApprox(path[49].pose, 1e-12));
    });
    convert::OdometryData od;
    od.stamp = stamp;
    od.frame_id = "map";
    od.child_frame_id = "lidar";
    od.T_parent_child = some_pose(1);
    od.pose_covariance.setIdentity();
    od.linear_velocity = {1, 2, 3};
    roundtrip<msg::Odometry>(*convert::to_msg(od), [&](const msg::Odometry& r) {
        const convert::OdometryData o = convert::from_msg(r);
        EXPECT_EQ(o.child_frame_id, "lidar");
        EXPECT_EQ(o.pose_covariance, od.pose_covariance);
        EXPECT_EQ(o.linear_velocity, od.linear_velocity);
    });
    convert::PoseGraphData g;
    g.frame_id = "map";
    g.revision = 3;
    for (std::uint64_t i = 0; i < 20; ++i) g.anchors.push_back({i, some_pose(i)});
    g.edges.push_back({0, 19, convert::GraphEdgeKind::kLoop, some_pose(5),
                       Eigen::Matrix<double, 6, 6>::Identity()});
    roundtrip<msg::PoseGraph>(*convert::to_msg(g), [&](const msg::PoseGraph& r) {
        const convert::PoseGraphData o = convert::from_msg(r);
        ASSERT_EQ(o.anchors.size(), 20u);
        ASSERT_EQ(o.edges.size(), 1u);
        EXPECT_EQ(o.edges[0].kind, convert::GraphEdgeKind::kLoop);
        EXPECT_TRUE(o.anchors[19].T_map_anchor.isApprox(g.anchors[19].T_map_anchor, 1e-12));
    });
    convert::LoopClosureData l;
    l.frame_id = "map";
    l.from_map_id = 1;
    l.to_map_id = 30;
    l.score = 0.12f;
    l.accepted = true;
    roundtrip<msg::LoopClosure>(*convert::to_msg(l), [&](const msg::LoopClosure& r) {
        const convert::LoopClosureData o = convert::from_msg(r);
        EXPECT_EQ(o.to_map_id, 30u);
        EXPECT_EQ(o.score, 0.12f);
        EXPECT_TRUE(o.accepted);
    });
}

TEST(Convert, TimeConversionsRoundTrip) {
    for (double s : {0.0, 0.5, 1.999999999, 1700000000.123456789, 12.0}) {
        const msg::Time t = convert::to_time(s);
        EXPECT_LT(t.nanosec, 1000000000u);
        EXPECT_NEAR(convert::to_seconds(t), s, 1e-6);
    }
}

TEST(Convert, PointCloud2WithShortDataIsRejected) {
    std::uint8_t data[16] = {};
    char x[] = "x", y[] = "y", z[] = "z";
    msg::PointField fields[3] = {{x, 0, 7, 1}, {y, 4, 7, 1}, {z, 8, 7, 1}};
    msg::PointCloud2 m{};
    m.height = 1;
    m.width = 2;  // says 2 points of 16 bytes, holds one
    m.point_step = 16;
    m.row_step = 32;
    m.fields._buffer = fields;
    m.fields._length = 3;
    m.data._buffer = data;
    m.data._length = 16;
    common::PointCloud out;
    EXPECT_EQ(convert::from_pointcloud2(m, out), "data holds 16 bytes, height * row_step says 32");
}
