#pragma once
// Alignment of two corresponding point sets (Umeyama 1991): rigid, or with one scale.
#include <Eigen/Geometry>
#include <vector>

namespace ltm::eval {

// The rigid transform T (rotation + translation, no scale) minimising
// sum_i |T * est[i] - ref[i]|^2 over the first min(est.size(), ref.size()) pairs.
// Identity for no pairs; a pure translation for one pair. Degenerate sets (collinear points)
// give one of the minimisers.
Eigen::Isometry3d umeyama_se3(const std::vector<Eigen::Vector3d>& est,
                              const std::vector<Eigen::Vector3d>& ref);

// The similarity minimising sum_i |s R est[i] + t - ref[i]|^2 (Umeyama's eq. 40-42): returns T
// (R, t) and sets *scale = s, so that ref[i] ~ T * (s est[i]). s = 1 (and T = umeyama_se3) when the
// est points do not spread (fewer than two distinct points).
Eigen::Isometry3d umeyama_sim3(const std::vector<Eigen::Vector3d>& est,
                               const std::vector<Eigen::Vector3d>& ref, double* scale);

}  // namespace ltm::eval
