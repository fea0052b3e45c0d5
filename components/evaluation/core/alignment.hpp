#pragma once
// Rigid alignment of two corresponding point sets (Umeyama 1991, without scale).
#include <Eigen/Geometry>
#include <vector>

namespace ltm::eval {

// The rigid transform T (rotation + translation, no scale) minimising
// sum_i |T * est[i] - ref[i]|^2 over the first min(est.size(), ref.size()) pairs.
// Identity for no pairs; a pure translation for one pair. Degenerate sets (collinear points)
// give one of the minimisers.
Eigen::Isometry3d umeyama_se3(const std::vector<Eigen::Vector3d>& est,
                              const std::vector<Eigen::Vector3d>& ref);

}  // namespace ltm::eval
