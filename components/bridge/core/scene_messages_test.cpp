#include "bridge/core/scene_messages.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "bridge/core/ros2msg_schemas.hpp"

namespace ltm::bridge {
namespace {

std::uint32_t u32_at(const std::vector<std::uint8_t>& b, std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

TEST(PointCloud2Cdr, LayoutOfROS2) {
    const std::vector<Eigen::Vector3f> points = {{1.f, 2.f, 3.f}, {4.f, 5.f, 6.f}};
    const auto b = point_cloud2_cdr(points, "map", Stamp{7, 8});
    // encapsulation, stamp, "map" (4 + 4 bytes), height, width.
    ASSERT_GE(b.size(), 28u);
    EXPECT_EQ(b[0], 0x00);
    EXPECT_EQ(b[1], 0x01);
    EXPECT_EQ(u32_at(b, 4), 7u);
    EXPECT_EQ(u32_at(b, 8), 8u);
    EXPECT_EQ(u32_at(b, 12), 4u);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(b.data() + 16)), "map");
    EXPECT_EQ(u32_at(b, 20), 1u);
    EXPECT_EQ(u32_at(b, 24), 2u);
    // The data are the last 24 bytes before is_dense, after their length.
    ASSERT_EQ(b.back(), 1);  // is_dense
    EXPECT_EQ(u32_at(b, b.size() - 1 - 24 - 4), 24u);
    float xyz[6];
    std::memcpy(xyz, b.data() + b.size() - 1 - 24, 24);
    EXPECT_FLOAT_EQ(xyz[0], 1.f);
    EXPECT_FLOAT_EQ(xyz[5], 6.f);
}

TEST(SceneUpdateCdr, OneTriangleListOrADeletion) {
    MeshChunk chunk;
    chunk.id = "mesh/3";
    chunk.frame_id = "map";
    chunk.vertices = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    chunk.triangles = {0, 1, 2};
    const auto b = scene_update_cdr(chunk);
    EXPECT_EQ(u32_at(b, 4), 0u);  // no deletion
    EXPECT_EQ(u32_at(b, 8), 1u);  // one entity
    // Its last fields: the three indices, then no text, no model.
    EXPECT_EQ(u32_at(b, b.size() - 8), 0u);
    EXPECT_EQ(u32_at(b, b.size() - 12), 2u);
    EXPECT_EQ(u32_at(b, b.size() - 24), 3u);  // the index count

    chunk.triangles.clear();
    const auto d = scene_update_cdr(chunk);
    EXPECT_EQ(u32_at(d, 4), 1u);             // one deletion
    EXPECT_EQ(u32_at(d, d.size() - 4), 0u);  // no entity
}

TEST(Ros2msgSchemas, EveryTypeUsedOnceAfterTheDefinition) {
    const std::string s = ros2msg_schema("nav_msgs/msg/Odometry");
    ASSERT_EQ(s.rfind("std_msgs/Header header\n", 0), 0u) << s;
    for (const char* dep :
         {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/Pose", "geometry_msgs/Point",
          "geometry_msgs/Quaternion", "geometry_msgs/PoseWithCovariance", "geometry_msgs/Twist",
          "geometry_msgs/TwistWithCovariance", "geometry_msgs/Vector3"}) {
        const std::string line = "\nMSG: " + std::string(dep) + "\n";
        const auto at = s.find(line);
        EXPECT_NE(at, std::string::npos) << dep;
        EXPECT_EQ(s.find(line, at + 1), std::string::npos) << dep << " twice";
    }
    EXPECT_EQ(ros2msg_schema("tf2_msgs/TFMessage"), ros2msg_schema("tf2_msgs/msg/TFMessage"));
    EXPECT_NE(ros2msg_schema("foxglove_msgs/msg/SceneUpdate").find("MSG: foxglove_msgs/Color"),
              std::string::npos);
    EXPECT_EQ(ros2msg_schema("ltm_msgs/msg/LocalMap"), "");  // ltm's own: omgidl
    EXPECT_EQ(ros2msg_schema("garbage"), "");
}

}  // namespace
}  // namespace ltm::bridge
