#include "runtime/topic_names.hpp"

#include <gtest/gtest.h>

using namespace ltm::runtime;

TEST(TopicNames, RosMapping) {
    std::string err;
    EXPECT_EQ(resolve_name("points", "/robot", "odom", err), "/robot/points");
    EXPECT_EQ(resolve_name("points", "", "odom", err), "/points");
    EXPECT_EQ(resolve_name("points", "robot/", "odom", err), "/robot/points");
    EXPECT_EQ(resolve_name("/kitti/points", "/robot", "odom", err), "/kitti/points");
    EXPECT_EQ(resolve_name("~/debug", "/robot", "odom", err), "/robot/odom/debug");
    EXPECT_EQ(dds_topic_name("/robot/points"), "rt/robot/points");
}

TEST(TopicNames, InvalidNames) {
    std::string err;
    EXPECT_EQ(resolve_name("a//b", "", "c", err), "");
    EXPECT_NE(err.find("empty name token"), std::string::npos);
    EXPECT_EQ(resolve_name("a-b", "", "c", err), "");
    EXPECT_NE(err.find("not allowed"), std::string::npos);
    EXPECT_EQ(resolve_name("1abc", "", "c", err), "");
    EXPECT_EQ(resolve_name("~x", "", "c", err), "");
    EXPECT_EQ(resolve_name("", "", "c", err), "");
}
