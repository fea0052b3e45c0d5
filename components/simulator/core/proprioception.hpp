#pragma once
// What the robot feels of its own motion (issue 27, item 5): an IMU (gyro and accelerometer with
// a turn-on bias, a bias random walk and white noise) and a wheel odometry (a planar dead
// reckoning of forward speed and yaw rate with a scale error, slip while turning and noise), both
// sampled at their own rates from the true trajectory. Deterministic for a seed.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <vector>

namespace ltm::sim {

class Simulator;

struct ImuConfig {
    double rate = 200.0;                                            // [Hz]
    Eigen::Isometry3d T_lidar_imu = Eigen::Isometry3d::Identity();  // where the IMU sits
    double gyro_noise = 1e-3;      // [rad/s/sqrt(Hz)] white noise density (a MEMS gyro)
    double gyro_bias = 0.005;      // [rad/s] 1-sigma turn-on bias per axis (0.29 deg/s)
    double gyro_bias_walk = 1e-5;  // [rad/s^2/sqrt(Hz)] bias random walk
    double accel_noise = 2e-3;     // [m/s^2/sqrt(Hz)]
    double accel_bias = 0.05;      // [m/s^2] 1-sigma turn-on bias per axis
};

struct WheelConfig {
    double rate = 50.0;  // [Hz]
    // The base frame (on the ground, x forward, z up) in the LiDAR frame.
    Eigen::Isometry3d T_lidar_base = Eigen::Isometry3d::Identity();
    double scale_error = 0.02;  // 1-sigma relative error of the distance (wheel radius), fixed
    double speed_noise = 0.01;  // [m/s/sqrt(Hz)]
    double turn_error = 0.05;   // 1-sigma relative error of the turn rate (track width), fixed
    double slip = 0.1;          // relative 1-sigma noise of the turn rate while turning (skid)
    double turn_noise = 2e-3;   // [rad/s/sqrt(Hz)]
};

struct ImuSample {
    double stamp = 0.0;
    Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // [rad/s] IMU frame
    Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // [m/s^2] specific force, IMU frame
};

struct WheelSample {
    double stamp = 0.0;
    Eigen::Isometry3d T_odom_base = Eigen::Isometry3d::Identity();  // planar dead reckoning
    Eigen::Vector3d linear = Eigen::Vector3d::Zero();               // [m/s] base frame
    Eigen::Vector3d angular = Eigen::Vector3d::Zero();              // [rad/s] base frame
};

// Where ltm_sim and the simulator component put the IMU unless told otherwise: 5 cm behind and
// 8 cm below the LiDAR, turned 90 deg about z (a mount that is not the LiDAR's own frame).
Eigen::Isometry3d default_imu_mount();

// The true T_world_lidar at a time.
using PoseAt = std::function<Eigen::Isometry3d(double)>;

// The true angular velocity [rad/s] and specific force [m/s^2] of a frame T_lidar_frame carried
// by the LiDAR, in that frame (central differences of `pose` over `h` s).
void true_inertial(const PoseAt& pose, double t, const Eigen::Isometry3d& T_lidar_frame,
                   Eigen::Vector3d* rate, Eigen::Vector3d* specific_force, double h = 1e-3);

class ImuSimulator {
  public:
    ImuSimulator(const ImuConfig& config, std::uint64_t seed);
    // Samples at the times k / rate in [t0, t1), appended to `out`; successive calls continue the
    // bias walk (pieces of a trajectory, e.g. between kidnaps).
    void run(const PoseAt& pose, double t0, double t1, std::vector<ImuSample>* out);
    const Eigen::Vector3d& gyro_bias() const { return gyro_bias_; }
    const Eigen::Vector3d& accel_bias() const { return accel_bias_; }

  private:
    ImuConfig config_;
    std::uint64_t seed_;
    Eigen::Vector3d gyro_bias_, accel_bias_;
};

class WheelSimulator {
  public:
    WheelSimulator(const WheelConfig& config, std::uint64_t seed);
    // As ImuSimulator::run. The dead reckoning starts at identity with the first sample and
    // integrates across pieces (a kidnap is not seen by the wheels).
    void run(const PoseAt& pose, double t0, double t1, std::vector<WheelSample>* out);
    double scale() const { return scale_; }      // the distance factor drawn
    double turn_scale() const { return turn_; }  // the turn rate factor drawn

  private:
    WheelConfig config_;
    std::uint64_t seed_;
    double scale_, turn_;
    bool started_ = false;
    double x_ = 0.0, y_ = 0.0, yaw_ = 0.0, last_ = 0.0;
};

// Both, for the scans [first, last) of a simulator: from the first scan's stamp to the last
// one's sweep end, in pieces between kidnaps (nothing while the robot is carried).
void simulate_proprioception(const Simulator& sim, std::size_t first, std::size_t last,
                             ImuSimulator* imu, WheelSimulator* wheel,
                             std::vector<ImuSample>* imu_out, std::vector<WheelSample>* wheel_out);

}  // namespace ltm::sim
