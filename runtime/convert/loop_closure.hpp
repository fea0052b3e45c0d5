#pragma once
// ltm_msgs/LoopClosure: a loop between two local maps, found from two keyframes.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

struct LoopClosureData {
    msg::Time stamp{};
    std::string frame_id;                          // the map frame
    std::uint64_t from_map_id = 0, to_map_id = 0;  // earlier keyframe's local map, current one's
    std::uint64_t from_keyframe_id = 0, to_keyframe_id = 0;
    Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();  // between the anchors
    Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Identity();
    float score = 0.f;     // descriptor distance (lower is closer)
    float fitness = 0.f;   // verification inlier ratio
    float residual = 0.f;  // verification RMS residual [m]
    bool accepted = false;
};

Owned<msg::LoopClosure> to_msg(const LoopClosureData& loop);
LoopClosureData from_msg(const msg::LoopClosure& message);

}  // namespace ltm::convert
