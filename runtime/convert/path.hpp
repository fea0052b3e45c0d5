#pragma once
// geometry_msgs/PoseStamped and nav_msgs/Path <-> common::StampedPose and common::Trajectory.
// Every pose of a path carries the path's frame.
#include <string>

#include "common/core/trajectory_io.hpp"
#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

Owned<msg::PoseStamped> to_msg(const common::StampedPose& pose, const std::string& frame_id);
common::StampedPose from_msg(const msg::PoseStamped& message);

// The path's own stamp is `stamp` (zero: none).
Owned<msg::Path> to_msg(const common::Trajectory& poses, const std::string& frame_id,
                        double stamp = 0.0);
common::Trajectory from_msg(const msg::Path& message);

}  // namespace ltm::convert
