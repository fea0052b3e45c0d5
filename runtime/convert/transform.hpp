#pragma once
// geometry_msgs/Transform(Stamped) <-> Eigen: a frame's pose in its parent, T_parent_child.
#include <Eigen/Geometry>
#include <string>

#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

msg::Transform to_transform(const Eigen::Isometry3d& T);
Eigen::Isometry3d to_isometry(const msg::Transform& transform);

struct TransformData {
    msg::Time stamp{};
    std::string parent_frame_id, child_frame_id;
    Eigen::Isometry3d T_parent_child = Eigen::Isometry3d::Identity();
};

Owned<msg::TransformStamped> to_msg(const TransformData& transform);
TransformData from_msg(const msg::TransformStamped& message);

}  // namespace ltm::convert
