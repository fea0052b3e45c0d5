#include "runtime/idl_schema.hpp"

#include <gtest/gtest.h>

#include "runtime/messages.hpp"

using namespace ltm::runtime;

TEST(IdlSchema, SelfContainedInDependencyOrder) {
    const std::string text = idl_schema_text("sensor_msgs/msg/PointCloud2");
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.find("#include"), std::string::npos);
    EXPECT_EQ(text.find("#ifndef"), std::string::npos);
    const auto time = text.find("struct Time_");
    const auto header = text.find("struct Header_");
    const auto field = text.find("struct PointField_");
    const auto cloud = text.find("struct PointCloud2_");
    ASSERT_NE(cloud, std::string::npos);
    EXPECT_LT(time, header);
    EXPECT_LT(header, cloud);
    EXPECT_LT(field, cloud);
    // Each dependency once, even when included twice (Odometry reaches Header twice).
    const std::string odom = idl_schema_text("nav_msgs/msg/Odometry");
    EXPECT_EQ(odom.find("struct Header_"), odom.rfind("struct Header_"));
    EXPECT_EQ(idl_schema_text("no_msgs/msg/Nothing"), "");
}

TEST(IdlSchema, EveryKnownTypeHasItsIdl) {
    for (const auto& t : known_message_types())
        EXPECT_FALSE(idl_schema_text(t.ros_name).empty()) << t.ros_name;
}
