#pragma once
// ROS 2 names (ros2/design "topic and service name mapping"): relative names live in the host's
// namespace, "~/x" in the component's, "/x" is absolute; the DDS topic is "rt" + absolute name.
#include <string>

namespace ltm::runtime {

// Normalises a namespace: "" or "/" -> "", "robot" -> "/robot", "/a/b/" -> "/a/b".
std::string normalise_namespace(const std::string& ns);
// Absolute ROS name of `name` for a component `component` in namespace `ns`.
// Returns "" and sets `error` when the name is invalid.
std::string resolve_name(const std::string& name, const std::string& ns,
                         const std::string& component, std::string& error);
// "/robot/points" -> "rt/robot/points".
std::string dds_topic_name(const std::string& absolute_name);

}  // namespace ltm::runtime
