#pragma once
// maintenance::ChangeSet <-> ltm_msgs/MapChangeSet (one SegmentChange a segment, its voxel centres
// as x y z floats). The map's world frame is the message's frame_id; `pass` numbers the
// publisher's passes.
#include <cstdint>
#include <string>

#include "maintenance/core/change_set.hpp"
#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::maintenance {

std::uint8_t to_msg_reason(ChangeReason reason);

convert::Owned<msg::MapChangeSet> to_msg(const ChangeSet& changes, std::uint32_t pass, double stamp,
                                         const std::string& frame_id);

// The ChangeSet of a message (any sample: it is checked). Throws std::invalid_argument, one line
// naming the change, for an unknown reason or voxels that are not x y z triples.
ChangeSet from_msg(const msg::MapChangeSet& m);

}  // namespace ltm::maintenance
