#pragma once
// The header stamp of a serialized ROS-style message (std_msgs/Header first): the budget probe
// reads it from the raw CDR without decoding the message (a scan's points are not touched).
#include <cstddef>
#include <cstdint>
#include <optional>

namespace ltm::bench {

// Seconds of header.stamp (int32 sec, uint32 nanosec right after the 4-byte encapsulation
// header, in the byte order it names); nullopt when the data is too short.
std::optional<double> cdr_header_stamp(const std::uint8_t* data, std::size_t size);

}  // namespace ltm::bench
