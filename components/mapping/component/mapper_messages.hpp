#pragma once
// The mapper's state as message data (runtime/convert builds the messages): the pose graph by
// local map ids, a loop closure, and this session's corrected keyframe path.
#include <string>

#include "common/core/trajectory_io.hpp"
#include "mapping/core/mapper.hpp"
#include "runtime/convert/loop_closure.hpp"
#include "runtime/convert/pose_graph.hpp"

namespace ltm::mapping {

// Anchors at their optimised poses and the active edges, both named by local map ids.
convert::PoseGraphData graph_data(const Mapper& mapper, const std::string& frame_id);

// A loop the mapper has just closed, between the local maps of its two graph nodes.
convert::LoopClosureData loop_data(const Mapper& mapper, const LoopClosure& loop,
                                   const msg::Time& stamp, const std::string& frame_id);

// This session's keyframes (not a loaded map's) at their optimised poses.
common::Trajectory session_path(const Mapper& mapper);
// The same for one session (a robot's, when several map at once).
common::Trajectory session_path(const Mapper& mapper, std::uint32_t session);

}  // namespace ltm::mapping
