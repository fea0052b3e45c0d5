#pragma once
// Reference revisits of a trajectory, for scoring loop closure in the benchmark: frame q revisits
// frame m when m is at least `min_gap` frames earlier and within `radius` metres; consecutive
// revisiting frames (gaps up to `join` frames) form one revisit segment. A segment is closed when
// some loop's query frame lies in it.
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"

namespace ltm::mapping::bench {

struct RevisitSegment {
    std::size_t first = 0, last = 0;  // query frames [first, last]
    bool closed = false;
};

std::vector<RevisitSegment> revisit_segments(const common::PoseList& reference, double radius,
                                             std::size_t min_gap, std::size_t join = 10);

// Marks the segments holding one of the query frames.
void mark_closed(const std::vector<std::size_t>& query_frames,
                 std::vector<RevisitSegment>* segments);

// The longest run of revisiting frames (inside a segment) with no query frame: on a route driven
// many times the laps after the first are one long revisit, closed by its first loop; this says
// how long the mapper went without one.
std::size_t longest_unclosed_run(const std::vector<RevisitSegment>& segments,
                                 std::vector<std::size_t> query_frames);

}  // namespace ltm::mapping::bench
