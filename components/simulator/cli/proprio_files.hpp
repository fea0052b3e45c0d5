#pragma once
// The robot's own motion sensors beside a simulated run's scans (text, one sample a line):
//   imu.txt             stamp gx gy gz ax ay az      IMU frame [s, rad/s, m/s^2]
//   wheel_odometry.txt  stamp x y z qx qy qz qw vx vy vz wx wy wz
//                       base frame in the wheel odometry frame; twist in the base frame
//   extrinsics.txt      NAME x y z qx qy qz qw       T_lidar_imu, T_lidar_base: the sensor's
//                       frame in the LiDAR frame
// Comment lines start with '#' (the imu.txt header states the drawn biases, the wheel file's the
// drawn scale errors: the truth a benchmark may compare with).
#include <string>
#include <vector>

#include "simulator/core/proprioception.hpp"

namespace ltm::sim::cli {

void write_imu(const std::string& path, const std::vector<ImuSample>& samples,
               const ImuConfig& config, const ImuSimulator& imu);
void write_wheel_odometry(const std::string& path, const std::vector<WheelSample>& samples,
                          const WheelConfig& config, const WheelSimulator& wheel);
void write_extrinsics(const std::string& path, const ImuConfig& imu, const WheelConfig& wheel);

}  // namespace ltm::sim::cli
