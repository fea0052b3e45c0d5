#pragma once
// The robot's motion sensors beside a scan folder, as ltm_sim writes them
// (simulator/cli/proprio_files.hpp): imu.txt, wheel_odometry.txt and extrinsics.txt. Read for
// `ltm_bench_odometry --prior`.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "odometry/core/motion_prior.hpp"

namespace ltm::odometry::bench {

struct PriorSamples {
    std::vector<double> imu_stamps;
    std::vector<Eigen::Vector3d> gyro;  // [rad/s] IMU frame
    std::vector<double> wheel_stamps;
    std::vector<Eigen::Isometry3d> wheel_poses;  // T_odom_base
};

// Reads DIR/imu.txt (when `imu`), DIR/wheel_odometry.txt (when `wheel`) and sets the extrinsics
// of `config` from DIR/extrinsics.txt. Throws common::IoError (file and line) on a missing or
// malformed file.
PriorSamples read_prior_samples(const std::string& dir, bool imu, bool wheel,
                                MotionPriorConfig* config);

// Feeds `prior` every sample up to `until` not fed yet (cursors in `next_imu`, `next_wheel`).
void feed_prior(const PriorSamples& s, double until, std::size_t* next_imu, std::size_t* next_wheel,
                MotionPrior* prior);

}  // namespace ltm::odometry::bench
