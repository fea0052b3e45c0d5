#pragma once
// Relative pose error over a fixed frame delta (Sturm et al. 2012, TUM RGB-D benchmark):
// E_i = (ref_i^-1 ref_{i+d})^-1 (est_i^-1 est_{i+d}); its translation norm and rotation angle.
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "evaluation/core/stats.hpp"

namespace ltm::eval {

struct RpeResult {
    ErrorStats translation;   // [m] per `delta` frames
    ErrorStats rotation_deg;  // [deg] per `delta` frames
    std::size_t delta = 1;    // frames
};

// Over the first min(est.size(), ref.size()) poses; empty stats when fewer than delta + 1.
// delta 0 is treated as 1.
RpeResult compute_rpe(const common::PoseList& est, const common::PoseList& ref,
                      std::size_t delta = 1);

// The per-pair errors behind compute_rpe, pair i being frames (i, i + delta).
void rpe_errors(const common::PoseList& est, const common::PoseList& ref, std::size_t delta,
                std::vector<double>& translation_m, std::vector<double>& rotation_deg);

// Rotation angle of a rotation matrix [rad], robust to round-off.
double rotation_angle(const Eigen::Matrix3d& R);

}  // namespace ltm::eval
