#pragma once
// The IDL text of a message type, self-contained (every #include inlined once, in dependency
// order): what an MCAP `omgidl` schema carries so that any reader decodes ltm's CDR without ltm.
#include <map>
#include <string>

namespace ltm::runtime {

// Every file of idl/, by path relative to idl/ ("sensor_msgs/msg/PointCloud2.idl").
const std::map<std::string, std::string>& idl_sources();

// "sensor_msgs/msg/PointCloud2" -> the self-contained IDL; "" when the type is unknown.
std::string idl_schema_text(const std::string& ros_name);

}  // namespace ltm::runtime
