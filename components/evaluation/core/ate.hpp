#pragma once
// Absolute trajectory error: position differences after a rigid (no scale) alignment.
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"

namespace ltm::eval {

struct AteResult {
    double rmse = 0.0, mean = 0.0, median = 0.0, max = 0.0;  // [m]
    std::size_t n = 0;                                       // poses compared
};

// Pose i of `estimate` is compared with pose i of `reference`, over the first
// min(estimate.size(), reference.size()) poses. With `align`, the estimate's positions are first
// mapped by umeyama_se3(estimate positions, reference positions).
AteResult compute_ate(const common::PoseList& estimate, const common::PoseList& reference,
                      bool align = true);

// The same, with what plots need: the alignment used and the error of every pose.
struct AteDetail {
    AteResult stats;
    Eigen::Isometry3d T_ref_est = Eigen::Isometry3d::Identity();  // identity without `align`
    std::vector<double> errors;                                   // [m], one per pose compared
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};
AteDetail compute_ate_detail(const common::PoseList& estimate, const common::PoseList& reference,
                             bool align = true);

// Positions of poses, and every pose left-multiplied by T.
std::vector<Eigen::Vector3d> positions(const common::PoseList& poses);
common::PoseList transform_poses(const Eigen::Isometry3d& T, const common::PoseList& poses);

}  // namespace ltm::eval
