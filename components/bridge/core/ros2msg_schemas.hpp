#pragma once
// ros2msg schemas (ROS 2 .msg text with its dependencies, as ROS 2's own tools and Foxglove write
// them) for the topics whose types are ROS 2's: ltm's mirrors in idl/ (sensor_msgs/PointCloud2,
// nav_msgs/Odometry, tf2_msgs/TFMessage, ...) and the Foxglove scene types the bridge makes
// (foxglove_msgs/SceneUpdate). Foxglove then decodes and draws them by their ROS names.
#include <string>

namespace ltm::bridge {

// The schema of `ros_name` ("nav_msgs/msg/Odometry" or "nav_msgs/Odometry"): its definition, then
// each type it uses once, after a line of 80 '=' and "MSG: pkg/Type". "" when `ros_name` is not a
// ROS 2 type this table knows (ltm's own types keep their omgidl schema).
std::string ros2msg_schema(const std::string& ros_name);

}  // namespace ltm::bridge
