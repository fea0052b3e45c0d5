#pragma once
// The KITTI odometry metric, as the devkit's evaluate_odometry.cpp defines it: for every first
// frame (every `step` frames) and every segment length L, the last frame is the first one whose
// distance travelled along the reference exceeds L; the error is the relative pose error
// (est_delta^-1 * ref_delta) of that segment, its translation and its rotation angle divided by L.
// The metric is the plain average over all segments of all lengths. One deliberate difference:
// the rotation angle is computed as atan2(|skew part|, (trace - 1) / 2) instead of the devkit's
// acos((trace - 1) / 2), which loses most digits for small angles when the files' rotations are
// rounded (KITTI's poses carry 7 digits); the quantity defined is the same.
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"

namespace ltm::eval {

struct KittiMetric {
    double translation_pct = 0.0;        // average translation error / length [%]
    double rotation_deg_per_100m = 0.0;  // average rotation error / length [deg / 100 m]
    std::size_t segments = 0;            // segments averaged (0: run too short, both values 0)
    bool short_segments = false;         // true when the 10..50 m lengths were used
};

struct KittiSegmentError {
    std::size_t first_frame = 0, last_frame = 0;
    double length = 0.0;       // nominal segment length [m]
    double translation = 0.0;  // translation error / length [-]
    double rotation = 0.0;     // rotation error / length [rad/m]
};

// The devkit's lengths, and the short ones used for runs under 800 m.
std::vector<double> kitti_lengths();        // 100, 200, ..., 800 m
std::vector<double> kitti_short_lengths();  // 10, 20, ..., 50 m

// Distance travelled along the poses' positions, from 0 at pose 0 [m].
std::vector<double> distances_travelled(const common::PoseList& poses);

// Every segment of the given lengths, first frames every `step` frames, over the first
// min(est.size(), ref.size()) poses.
std::vector<KittiSegmentError> kitti_segment_errors(const common::PoseList& est,
                                                    const common::PoseList& ref,
                                                    const std::vector<double>& lengths,
                                                    std::size_t step = 10);

// Averages of the segments above; short_segments is left false.
KittiMetric kitti_metric_for_lengths(const common::PoseList& est, const common::PoseList& ref,
                                     const std::vector<double>& lengths, std::size_t step = 10);

// The devkit metric (100..800 m) when the reference is at least 800 m long, otherwise the
// 10..50 m lengths with short_segments = true.
KittiMetric compute_kitti_metric(const common::PoseList& est, const common::PoseList& ref);

}  // namespace ltm::eval
