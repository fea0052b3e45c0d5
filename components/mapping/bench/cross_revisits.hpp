#pragma once
// Reference revisits between two robots driving at once (the multi-robot benchmark): frame i of
// robot A revisits robot B when B was within `radius` metres of A's pose at frame i or earlier
// (both start together, one frame a step); consecutive revisiting frames (gaps up to `join`)
// form one segment. A segment is closed when a loop between the two robots has robot A's frame
// (its query or its match) in it.
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "mapping/bench/revisits.hpp"

namespace ltm::mapping::bench {

std::vector<RevisitSegment> cross_revisit_segments(const common::PoseList& a,
                                                   const common::PoseList& b, double radius,
                                                   std::size_t join = 10);

}  // namespace ltm::mapping::bench
