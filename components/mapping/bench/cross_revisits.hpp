#pragma once
// Reference revisits between two robots driving at once (the multi-robot benchmark): frame i of
// robot A revisits robot B when B was within `radius` metres of A's pose at frame i or earlier
// (both start together, one frame a step); consecutive revisiting frames (gaps up to `join`)
// form one segment. A segment is closed when a loop between the two robots has robot A's frame
// (its query or its match) in it (mark_closed, revisits.hpp), or when such a loop joins the local
// map one of its frames was registered in with the local map of a frame of robot B's within
// `radius` of it (by then): local maps are rigid in the graph, a loop on one places all of its
// frames, and the mapper keeps at most max_loops_per_anchor_pair loops between two local maps, so
// the frames of a joined pair that come later get no loop of their own.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "mapping/bench/revisits.hpp"

namespace ltm::mapping::bench {

std::vector<RevisitSegment> cross_revisit_segments(const common::PoseList& a,
                                                   const common::PoseList& b, double radius,
                                                   std::size_t join = 10);

// Marks the segments of robot A (poses a, the local map of each frame a_maps) whose local map at a
// revisiting frame a loop (frames: A's, B's) joins with B's local map at a frame of B's within
// `radius` of it (by then).
void mark_closed_by_local_maps(const common::PoseList& a, const common::PoseList& b,
                               const std::vector<std::uint64_t>& a_maps,
                               const std::vector<std::uint64_t>& b_maps, double radius,
                               const std::vector<std::pair<std::size_t, std::size_t>>& loops,
                               std::vector<RevisitSegment>* segments);

}  // namespace ltm::mapping::bench
