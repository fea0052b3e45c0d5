#pragma once
// Loop-closure (place recognition) quality against ground-truth revisits.
//
// A detected loop is a pair (query, match): the query frame recognised the place of the match
// frame, seen earlier (or in another session). With the reference positions:
//   true revisit  distance(query, match) <= revisit_radius and, within one session,
//                 query - match >= min_frame_gap (pairs closer in time are not loops);
//   precision     true detected loops / detected loops (pairs under the frame gap are counted
//                 as `trivial` and left out);
//   recall        queries with a true detected loop / queries that have a revisit (some earlier
//                 frame, beyond the gap, within the radius);
//   F1            2 P R / (P + R).
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"

namespace ltm::eval {

struct LoopPair {
    std::size_t query = 0, match = 0;  // frame indices
    double score = 0.0;                // detector's score (kept, not used by the metric)
};

struct PlaceRecognitionConfig {
    double revisit_radius = 5.0;     // [m] a pair within this distance is the same place
    std::size_t min_frame_gap = 50;  // [frames] within one session, smaller gaps are no loops
};

struct PlaceRecognitionResult {
    std::size_t detected = 0;  // loops evaluated (trivial and out-of-range ones excluded)
    std::size_t true_positives = 0, false_positives = 0;
    std::size_t trivial = 0;          // detected pairs under the frame gap (excluded)
    std::size_t out_of_range = 0;     // pairs naming a frame with no reference pose (excluded)
    std::size_t revisit_queries = 0;  // queries with a true revisit
    std::size_t recalled_queries = 0;
    double precision = 0.0, recall = 0.0, f1 = 0.0;  // [0, 1]
    std::vector<bool> correct;                       // per input loop: a true revisit
};

// Within one session: query and match index the same reference trajectory. Loops are taken in
// either order (the later frame is the query).
PlaceRecognitionResult evaluate_loops(const std::vector<LoopPair>& loops,
                                      const common::PoseList& reference,
                                      const PlaceRecognitionConfig& config = {});

// Across sessions: queries index `query_reference`, matches index `match_reference`, both
// expressed in one world frame; no frame gap applies, and every query frame with a match-session
// frame within the radius is a revisit query.
PlaceRecognitionResult evaluate_cross_session_loops(const std::vector<LoopPair>& loops,
                                                    const common::PoseList& query_reference,
                                                    const common::PoseList& match_reference,
                                                    const PlaceRecognitionConfig& config = {});

}  // namespace ltm::eval
