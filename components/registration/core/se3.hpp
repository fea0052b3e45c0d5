#pragma once
// Small SE(3) helpers: exponential and logarithm maps, motion scaling. Twists are [rho; phi]
// (translation part first, rotation vector second), as in the covariance order of FrameResult.
#include <Eigen/Geometry>

namespace ltm::registration {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi);
Eigen::Vector3d so3_log(const Eigen::Matrix3d& R);
Eigen::Isometry3d se3_exp(const Vector6d& xi);
Vector6d se3_log(const Eigen::Isometry3d& T);

// exp(s * log(T)): the same screw motion, s times as far (s = 0.5: half-way).
Eigen::Isometry3d scale_motion(const Eigen::Isometry3d& T, double s);

// Rotation angle of T [rad].
double rotation_angle(const Eigen::Isometry3d& T);

}  // namespace ltm::registration
