#pragma once
// sensor_msgs/Imu: angular velocity and linear acceleration in the IMU's frame (and an
// orientation, unknown here: its covariance's first element is -1, as ROS 2 says).
#include <Eigen/Core>
#include <string>

#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

struct ImuData {
    double stamp = 0.0;  // [s]
    std::string frame_id = "imu";
    Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();     // [rad/s]
    Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();  // [m/s^2] specific force
    double gyro_variance = 0.0;                                     // per axis [(rad/s)^2]
    double accel_variance = 0.0;                                    // per axis [(m/s^2)^2]
};

Owned<msg::Imu> to_msg(const ImuData& imu);
// "" or why the message cannot be used (a rate or acceleration that is not finite).
std::string from_msg(const msg::Imu& message, ImuData* imu);

}  // namespace ltm::convert
