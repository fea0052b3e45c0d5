#include "simulator/core/proprioception.hpp"

#include <cmath>

#include "simulator/core/random.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::sim {
namespace {

constexpr double kGravity = 9.81;          // [m/s^2], world z up
constexpr double kGyroRange = 34.9;        // [rad/s] the gyro saturates (2000 deg/s)
constexpr double kAccelRange = 16 * 9.81;  // [m/s^2] the accelerometer saturates (16 g)

// Noise streams (hash_mix keys) of the draws.
enum Stream : std::uint64_t {
    kGyroBias = 1,
    kAccelBias,
    kGyroNoise,
    kGyroWalk,
    kAccelNoise,
    kWheelScale,
    kWheelTurn,
    kSpeedNoise,
    kTurnNoise,
    kSlip,
};

Eigen::Vector3d normal3(std::uint64_t seed, std::uint64_t stream, std::uint64_t k) {
    return {hash_normal(hash_mix(seed, stream, k, 0)), hash_normal(hash_mix(seed, stream, k, 1)),
            hash_normal(hash_mix(seed, stream, k, 2))};
}

Eigen::Vector3d log_rotation(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    return aa.axis() * aa.angle();
}

// First sample index at or after t on the grid k / rate.
std::int64_t first_index(double t, double rate) {
    return static_cast<std::int64_t>(std::ceil(t * rate - 1e-9));
}

}  // namespace

Eigen::Isometry3d default_imu_mount() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(-0.05, 0.0, -0.08);
    T.linear() = Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
}

void true_inertial(const PoseAt& pose, double t, const Eigen::Isometry3d& T_lidar_frame,
                   Eigen::Vector3d* rate, Eigen::Vector3d* specific_force, double h) {
    const Eigen::Isometry3d a = pose(t - h) * T_lidar_frame;
    const Eigen::Isometry3d b = pose(t) * T_lidar_frame;
    const Eigen::Isometry3d c = pose(t + h) * T_lidar_frame;
    *rate = log_rotation(a.linear().transpose() * c.linear()) / (2.0 * h);
    const Eigen::Vector3d acc =
        (a.translation() - 2.0 * b.translation() + c.translation()) / (h * h);
    *specific_force = b.linear().transpose() * (acc + Eigen::Vector3d(0.0, 0.0, kGravity));
}

ImuSimulator::ImuSimulator(const ImuConfig& config, std::uint64_t seed)
    : config_(config),
      seed_(seed),
      gyro_bias_(config.gyro_bias * normal3(seed, kGyroBias, 0)),
      accel_bias_(config.accel_bias * normal3(seed, kAccelBias, 0)) {}

void ImuSimulator::run(const PoseAt& pose, double t0, double t1, std::vector<ImuSample>* out) {
    const double rate = config_.rate;
    const double dt = 1.0 / rate;
    const double gyro_sigma = config_.gyro_noise * std::sqrt(rate);
    const double accel_sigma = config_.accel_noise * std::sqrt(rate);
    const double walk_sigma = config_.gyro_bias_walk * std::sqrt(dt);
    for (std::int64_t k = first_index(t0, rate); double(k) * dt < t1 - 1e-9; ++k) {
        ImuSample s;
        s.stamp = double(k) * dt;
        Eigen::Vector3d rate_true, force_true;
        true_inertial(pose, s.stamp, config_.T_lidar_imu, &rate_true, &force_true);
        const auto key = static_cast<std::uint64_t>(k);
        gyro_bias_ += walk_sigma * normal3(seed_, kGyroWalk, key);
        s.gyro = rate_true + gyro_bias_ + gyro_sigma * normal3(seed_, kGyroNoise, key);
        s.accel = force_true + accel_bias_ + accel_sigma * normal3(seed_, kAccelNoise, key);
        // A route's sudden starts and stops (no ramp) would be impossible forces: saturated.
        s.gyro = s.gyro.cwiseMax(-kGyroRange).cwiseMin(kGyroRange);
        s.accel = s.accel.cwiseMax(-kAccelRange).cwiseMin(kAccelRange);
        out->push_back(s);
    }
}

WheelSimulator::WheelSimulator(const WheelConfig& config, std::uint64_t seed)
    : config_(config),
      seed_(seed),
      scale_(1.0 + config.scale_error * hash_normal(hash_mix(seed, kWheelScale))),
      turn_(1.0 + config.turn_error * hash_normal(hash_mix(seed, kWheelTurn))) {}

void WheelSimulator::run(const PoseAt& pose, double t0, double t1, std::vector<WheelSample>* out) {
    const double rate = config_.rate;
    const double dt = 1.0 / rate;
    const double h = 1e-3;
    const Eigen::Isometry3d& B = config_.T_lidar_base;
    for (std::int64_t k = first_index(t0, rate); double(k) * dt < t1 - 1e-9; ++k) {
        const double t = double(k) * dt;
        const auto key = static_cast<std::uint64_t>(k);
        // The base's true forward speed and yaw rate, in its own frame.
        const Eigen::Isometry3d a = pose(t - h) * B, c = pose(t + h) * B;
        const Eigen::Isometry3d mid = pose(t) * B;
        const double v =
            (mid.linear().transpose() * (c.translation() - a.translation())).x() / (2.0 * h);
        const double w = log_rotation(a.linear().transpose() * c.linear()).z() / (2.0 * h);
        const double v_m = v * scale_ + config_.speed_noise * std::sqrt(rate) *
                                            hash_normal(hash_mix(seed_, kSpeedNoise, key));
        const double w_m =
            w * turn_ + std::abs(w) * config_.slip * hash_normal(hash_mix(seed_, kSlip, key)) +
            config_.turn_noise * std::sqrt(rate) * hash_normal(hash_mix(seed_, kTurnNoise, key));
        if (started_) {
            const double step = t - last_;
            const double heading = yaw_ + 0.5 * w_m * step;
            x_ += v_m * step * std::cos(heading);
            y_ += v_m * step * std::sin(heading);
            yaw_ += w_m * step;
        }
        started_ = true;
        last_ = t;
        WheelSample s;
        s.stamp = t;
        s.T_odom_base.translation() = Eigen::Vector3d(x_, y_, 0.0);
        s.T_odom_base.linear() = Eigen::AngleAxisd(yaw_, Eigen::Vector3d::UnitZ()).matrix();
        s.linear = Eigen::Vector3d(v_m, 0.0, 0.0);
        s.angular = Eigen::Vector3d(0.0, 0.0, w_m);
        out->push_back(s);
    }
}

void simulate_proprioception(const Simulator& sim, std::size_t first, std::size_t last,
                             ImuSimulator* imu, WheelSimulator* wheel,
                             std::vector<ImuSample>* imu_out, std::vector<WheelSample>* wheel_out) {
    const double period = sim.sensor().period();
    std::size_t i = first;
    while (i < last) {
        // A piece: scans i..j-1 with no kidnap between them.
        std::size_t j = i + 1;
        while (j < last && !sim.after_kidnap(j)) ++j;
        const double stamp = sim.stamp(i);
        const PoseAt pose = [&sim, i, stamp](double t) { return sim.pose_at(i, t - stamp); };
        const double end = sim.stamp(j - 1) + period;  // the piece's last sweep ends
        if (imu != nullptr) imu->run(pose, stamp, end, imu_out);
        if (wheel != nullptr) wheel->run(pose, stamp, end, wheel_out);
        i = j;
    }
}

}  // namespace ltm::sim
