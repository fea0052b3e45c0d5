#pragma once
// Stamps and poses between IDL messages and Eigen.
#include <Eigen/Geometry>

#include "runtime/messages.hpp"

namespace ltm::convert {

double to_seconds(const msg::Time& t);
msg::Time to_time(double seconds);

Eigen::Isometry3d to_isometry(const msg::Pose& pose);
msg::Pose to_pose(const Eigen::Isometry3d& T);

// Row-major 6x6 covariance/information arrays.
void to_array36(const Eigen::Matrix<double, 6, 6>& m, double out[36]);
Eigen::Matrix<double, 6, 6> from_array36(const double in[36]);

}  // namespace ltm::convert
