#pragma once
// ltm_msgs/PlaceDescriptor <-> a descriptor with the settings that made it (keyframe_digest.hpp).
#include <string>

#include "mapping/core/keyframe_digest.hpp"
#include "runtime/messages.hpp"

namespace ltm::mapping {

// The descriptor a message holds; empty when it holds none (rings 0). A message whose arrays do
// not have the shape it states, or of an unknown kind: empty, and `problem` (when given) says
// why in a few words.
MadeDescriptor from_msg(const msg::PlaceDescriptor& m, std::string* problem = nullptr);

// Fills `out` with views of `d`'s arrays (valid while `d` lives unchanged; see dds_string.hpp:
// the message must never reach a free function).
void borrow_into(const MadeDescriptor& d, msg::PlaceDescriptor* out);

}  // namespace ltm::mapping
