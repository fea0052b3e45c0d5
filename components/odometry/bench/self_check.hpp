#pragma once
// ltm_bench_odometry's self-check (issue 27): per scan, what the odometry says of itself (status,
// constrained directions, the search used, the published covariance) beside what the reference
// says (the step error), and the summary: degenerate scans, path length against the reference's,
// scans reported registered while more than 1 m off relative to the previous scan, and how many
// step errors fall within 3 sigma of the published covariance.
#include <cstdio>
#include <string>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "odometry/core/odometry.hpp"

namespace ltm::odometry::bench {

struct SelfCheck {
    std::size_t frames = 0, degenerate = 0, registered = 0, published = 0;
    std::size_t searched_along = 0, moved_along = 0, weak = 0;
    std::size_t spin_held = 0;  // degenerate scans held by the spin hold (tracking.spin_rate)
    double path = 0.0, reference_path = 0.0;  // [m]
    bool has_reference = false;
    std::size_t registered_off = 0;  // registered, step error > 1 m
    std::size_t steps = 0, within_3_sigma = 0;
    std::vector<double> step_error, mahalanobis;  // per frame (NaN: none)
};

// `results`: every frame's result (keyframe points dropped); `reference`: the kept reference
// poses, empty without one (then only the odometry's own side).
SelfCheck self_check(const std::vector<FrameResult>& results, const common::PoseList& reference);

void print_self_check(const SelfCheck& s, std::FILE* out);

// One CSV row a frame (header first); throws common::IoError when the file cannot be written.
void write_frame_log(const std::string& path, const std::vector<FrameResult>& results,
                     const std::vector<double>& ms, const SelfCheck& s);

}  // namespace ltm::odometry::bench
