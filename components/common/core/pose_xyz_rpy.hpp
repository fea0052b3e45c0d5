#pragma once
// A pose given as [x, y, z, roll, pitch, yaw] (m, deg): rotations about the fixed x, y, z axes in
// that order, R = Rz(yaw) Ry(pitch) Rx(roll), as ROS's static_transform_publisher. Launch configs
// give extrinsics this way (runtime/pose_param.hpp reads one from a component's parameters).
#include <Eigen/Geometry>
#include <vector>

namespace ltm::common {

// Throws std::invalid_argument (one line) on a count other than 6 or a value not finite.
Eigen::Isometry3d pose_from_xyz_rpy(const std::vector<double>& xyz_rpy_deg);

}  // namespace ltm::common
