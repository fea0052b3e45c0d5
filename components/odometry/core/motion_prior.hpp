#pragma once
// A motion prior from the robot (issue 27, item 5): gyro rates of an IMU and poses of a wheel
// odometry, integrated between two scan stamps into the LiDAR's relative motion with a
// covariance. The odometry uses it for its prediction (through spins the gyro turns the guess as
// the sensor turned) and, along the directions a registration could not observe, in place of the
// fit (a long straight road: the wheels say how far). Optional: without samples nothing changes.
// Synchronous and DDS-free; an adapter feeds the samples in time order.
#include <Eigen/Geometry>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "common/core/point_cloud.hpp"
#include "registration/core/se3.hpp"

namespace ltm::odometry {

struct MotionPriorConfig {
    // Where the sensors sit: the IMU's and the wheel odometry's base frame in the LiDAR frame.
    Eigen::Isometry3d T_lidar_imu = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_lidar_base = Eigen::Isometry3d::Identity();
    double gyro_noise = 1e-3;  // [rad/s/sqrt(Hz)] white noise density of the gyro
    double gyro_bias = 0.005;  // [rad/s] 1-sigma bias before it is learnt (per axis)
    // The gyro bias is learnt over windows of bias_window s of well-constrained fits: the share
    // bias_gain of the mean rate by which the gyro turned off the fits (0: never learnt).
    double bias_gain = 0.3;
    double bias_window = 2.0;   // [s]
    double wheel_scale = 0.05;  // 1-sigma relative error of the wheel distance (scale, slip)
    double wheel_turn = 0.2;    // 1-sigma relative error of the wheel odometry's turn
    // A fit whose motion differs from the prior's by more than gate_sigmas sigma and at least
    // gate_rotation / gate_translation is refused (a wrong minimum: a slide or a turn the robot
    // did not make).
    double gate_sigmas = 4.0;
    double gate_rotation = 2.0;     // [deg]
    double gate_translation = 0.3;  // [m]
    double max_gap = 0.2;           // [s] samples further apart than this: no prior across the gap
    double keep_seconds = 5.0;      // [s] samples older than this before the newest are dropped
};
// The first problem of the config (its key), or none.
std::optional<common::ConfigProblem> validate(const MotionPriorConfig& config);

// The LiDAR's motion from t0 to t1 as the prior sees it.
struct PriorMotion {
    Eigen::Isometry3d T_lidar0_lidar1 = Eigen::Isometry3d::Identity();
    // Of [translation (m); rotation vector (rad)] in the LiDAR frame at t0; a part not measured
    // (no wheels: translation; neither sensor: everything) has a large variance.
    registration::Matrix6d covariance = registration::Matrix6d::Identity();
    bool has_rotation = false;     // from the gyro, or the wheels' turn without an IMU
    bool has_translation = false;  // from the wheels
    Eigen::Vector3d rate = Eigen::Vector3d::Zero();  // mean angular velocity, LiDAR frame [rad/s]
};

class MotionPrior {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    explicit MotionPrior(const MotionPriorConfig& config = {});

    // A gyro sample [rad/s] in the IMU frame; a sample not after the last one is ignored.
    void add_imu(double stamp, const Eigen::Vector3d& gyro);
    // A wheel odometry pose of the base frame in its own odometry frame.
    void add_wheel(double stamp, const Eigen::Isometry3d& T_odom_base);
    bool has_imu() const { return !imu_.empty(); }
    bool has_wheel() const { return !wheel_.empty(); }

    // The motion from t0 to t1 (t0 < t1) if some sensor covers that span without a gap.
    std::optional<PriorMotion> between(double t0, double t1) const;

    // The pose at t1 predicted from the pose at t0: `fallback` (the constant-velocity guess) with
    // its rotation from the gyro (or wheels) and its translation from the wheels, where measured.
    Eigen::Isometry3d predict(const Eigen::Isometry3d& T_odom_lidar0, double t0, double t1,
                              const Eigen::Isometry3d& fallback) const;
    // "" when a fit from T0 (at t0) to `estimate` (at t1) agrees with the prior's motion (or the
    // prior has nothing to say), otherwise why not.
    std::string disagreement(const Eigen::Isometry3d& T_odom_lidar0, double t0, double t1,
                             const Eigen::Isometry3d& estimate) const;
    // The de-skew velocity of a scan with per-point times (body twist per second [v; w]): its
    // parts the prior measured over the sweep replace those of `velocity`.
    void deskew_velocity(const common::PointCloud& cloud, registration::Vector6d* velocity) const;
    // A registration from T0 (at t0) to `estimate` (at t1) that could not observe `directions`
    // (unit, [dt; dr * lever] in odometry axes, as RegistrationResult::degenerate_directions):
    // the motion along them is replaced by the prior's, where it measured them. Returns the pose.
    Eigen::Isometry3d fill_unobserved(const Eigen::Isometry3d& T_odom_lidar0, double t0, double t1,
                                      const Eigen::Isometry3d& estimate,
                                      const std::vector<registration::Vector6d>& directions,
                                      double lever) const;
    // The odometry's rotation at a scan and whether it was registered (along directions it could
    // not observe, the prior's own rotation was kept: nothing is learnt there). Over a window of
    // such fits a share of the gyro's disagreement with them is learnt as gyro bias (bounded by 3
    // gyro_bias); any other scan starts a new window.
    void observe(double stamp, const Eigen::Matrix3d& R_odom_lidar, bool registered);
    // The bias learnt so far, in the IMU frame [rad/s].
    const Eigen::Vector3d& gyro_bias() const { return bias_; }

  private:
    struct Gyro {
        double stamp;
        Eigen::Vector3d rate;
    };
    struct Wheel {
        double stamp;
        Eigen::Isometry3d T_odom_base;
    };
    // R_imu0_imu1 from the gyro over [t0, t1]; false when the samples do not cover it.
    bool integrate_gyro(double t0, double t1, Eigen::Matrix3d* R) const;
    // T_odom_base at t (interpolated); false outside the samples or across a gap.
    bool wheel_at(double t, Eigen::Isometry3d* T) const;

    MotionPriorConfig config_;
    std::deque<Gyro> imu_;
    std::deque<Wheel> wheel_;
    Eigen::Vector3d bias_ = Eigen::Vector3d::Zero();
    bool window_open_ = false;
    double window_stamp_ = 0.0;
    Eigen::Matrix3d window_rotation_ = Eigen::Matrix3d::Identity();  // R_odom_lidar at its start
};

}  // namespace ltm::odometry
