#pragma once
// nav_msgs/Odometry: the child frame's pose in the parent frame, with covariance, and its twist in
// the child frame.
#include <Eigen/Geometry>
#include <string>

#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

struct OdometryData {
    using Matrix6d = Eigen::Matrix<double, 6, 6>;
    msg::Time stamp{};
    std::string frame_id, child_frame_id;
    Eigen::Isometry3d T_parent_child = Eigen::Isometry3d::Identity();
    Matrix6d pose_covariance = Matrix6d::Zero();                 // (x y z rx ry rz)
    Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // [m/s], child frame
    Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // [rad/s], child frame
    Matrix6d twist_covariance = Matrix6d::Zero();
};

Owned<msg::Odometry> to_msg(const OdometryData& odometry);
OdometryData from_msg(const msg::Odometry& message);

// The same odometry with `frame_id` as its parent, given T_frame_parent (the old parent's pose in
// the new one): the pose is moved and its covariance rotated; the twist, in the child frame, stays.
OdometryData reparent(OdometryData odometry, const Eigen::Isometry3d& T_frame_parent,
                      const std::string& frame_id);

}  // namespace ltm::convert
