#include "odometry/core/motion_prior.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/core/config_check.hpp"

namespace ltm::odometry {
namespace {

constexpr double kUnmeasuredVariance = 1e4;        // a part of the motion the prior did not measure
constexpr double kWheelFloor = 0.01;               // [m] wheel translation sigma at standstill
constexpr double kTurnFloor = 0.2 * M_PI / 180.0;  // [rad] wheel turn sigma at standstill

bool orthonormal(const Eigen::Isometry3d& T) {
    return T.matrix().allFinite() &&
           (T.linear() * T.linear().transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6;
}

Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double s) {
    Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
    out.translation() = (1.0 - s) * a.translation() + s * b.translation();
    out.linear() = Eigen::Quaterniond(a.linear())
                       .slerp(s, Eigen::Quaterniond(b.linear()))
                       .normalized()
                       .toRotationMatrix();
    return out;
}

}  // namespace

std::optional<common::ConfigProblem> validate(const MotionPriorConfig& c) {
    const auto problem = [](const char* key, const char* what) {
        return std::optional<common::ConfigProblem>(common::ConfigProblem{key, what});
    };
    if (!orthonormal(c.T_lidar_imu)) return problem("imu_extrinsic", "not a rigid transform");
    if (!orthonormal(c.T_lidar_base)) return problem("wheel_extrinsic", "not a rigid transform");
    if (!(c.gyro_noise >= 0.0)) return problem("gyro_noise", "must be >= 0");
    if (!(c.gyro_bias >= 0.0)) return problem("gyro_bias", "must be >= 0");
    if (!(c.bias_window > 0.0)) return problem("bias_window", "must be > 0");
    if (!(c.bias_gain >= 0.0 && c.bias_gain <= 1.0))
        return problem("bias_gain", "must be in [0, 1]");
    if (!(c.wheel_scale >= 0.0)) return problem("wheel_scale", "must be >= 0");
    if (!(c.wheel_turn >= 0.0)) return problem("wheel_turn", "must be >= 0");
    if (!(c.gate_sigmas > 0.0)) return problem("gate_sigmas", "must be > 0");
    if (!(c.gate_rotation > 0.0)) return problem("gate_rotation", "must be > 0");
    if (!(c.gate_translation > 0.0)) return problem("gate_translation", "must be > 0");
    if (!(c.max_gap > 0.0)) return problem("max_gap", "must be > 0");
    if (!(c.keep_seconds > c.max_gap)) return problem("keep_seconds", "must be > max_gap");
    return std::nullopt;
}

MotionPrior::MotionPrior(const MotionPriorConfig& config) : config_(config) {
    common::throw_if(validate(config), "prior");
}

void MotionPrior::add_imu(double stamp, const Eigen::Vector3d& gyro) {
    if (!std::isfinite(stamp) || !gyro.allFinite()) return;
    if (!imu_.empty() && !(stamp > imu_.back().stamp)) return;
    imu_.push_back({stamp, gyro});
    while (imu_.front().stamp < stamp - config_.keep_seconds) imu_.pop_front();
}

void MotionPrior::add_wheel(double stamp, const Eigen::Isometry3d& T_odom_base) {
    if (!std::isfinite(stamp) || !T_odom_base.matrix().allFinite()) return;
    if (!wheel_.empty() && !(stamp > wheel_.back().stamp)) return;
    Eigen::Isometry3d T = T_odom_base;
    T.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
    wheel_.push_back({stamp, T});
    while (wheel_.front().stamp < stamp - config_.keep_seconds) wheel_.pop_front();
}

bool MotionPrior::integrate_gyro(double t0, double t1, Eigen::Matrix3d* R) const {
    if (imu_.empty() || !(t1 > t0)) return false;
    const double gap = config_.max_gap;
    if (t0 < imu_.front().stamp - gap || t1 > imu_.back().stamp + gap) return false;
    // The rate between samples is linear; beyond the first or last sample it is held.
    const auto rate_at = [this](double t, std::size_t k) -> Eigen::Vector3d {
        if (t <= imu_[k].stamp || k + 1 == imu_.size()) return imu_[k].rate;
        const double s = (t - imu_[k].stamp) / (imu_[k + 1].stamp - imu_[k].stamp);
        return (1.0 - std::min(1.0, s)) * imu_[k].rate + std::min(1.0, s) * imu_[k + 1].rate;
    };
    std::size_t k = std::upper_bound(imu_.begin(), imu_.end(), t0,
                                     [](double t, const Gyro& g) { return t < g.stamp; }) -
                    imu_.begin();
    k = k > 0 ? k - 1 : 0;
    Eigen::Matrix3d out = Eigen::Matrix3d::Identity();
    double a = t0;
    while (a < t1) {
        const bool last = k + 1 >= imu_.size();
        if (!last && imu_[k + 1].stamp - imu_[k].stamp > gap && a >= imu_[k].stamp) return false;
        const double b = last ? t1 : std::min(t1, std::max(a, imu_[k + 1].stamp));
        if (b > a) {
            const Eigen::Vector3d w = rate_at(0.5 * (a + b), k) - bias_;
            out = out * registration::so3_exp(w * (b - a));
        }
        a = b;
        if (!last) ++k;
    }
    *R = out;
    return true;
}

bool MotionPrior::wheel_at(double t, Eigen::Isometry3d* T) const {
    if (wheel_.empty()) return false;
    const double gap = config_.max_gap;
    if (t <= wheel_.front().stamp) {
        if (t < wheel_.front().stamp - gap) return false;
        *T = wheel_.front().T_odom_base;
        return true;
    }
    if (t >= wheel_.back().stamp) {
        if (t > wheel_.back().stamp + gap) return false;
        *T = wheel_.back().T_odom_base;
        return true;
    }
    const auto it = std::upper_bound(wheel_.begin(), wheel_.end(), t,
                                     [](double s, const Wheel& w) { return s < w.stamp; });
    const Wheel& b = *it;
    const Wheel& a = *(it - 1);
    if (b.stamp - a.stamp > gap) return false;
    *T = interpolate(a.T_odom_base, b.T_odom_base, (t - a.stamp) / (b.stamp - a.stamp));
    return true;
}

std::optional<PriorMotion> MotionPrior::between(double t0, double t1) const {
    if (!(t1 > t0)) return std::nullopt;
    PriorMotion m;
    m.covariance = registration::Matrix6d::Identity() * kUnmeasuredVariance;
    const double dt = t1 - t0;
    Eigen::Isometry3d W0, W1;
    if (wheel_at(t0, &W0) && wheel_at(t1, &W1)) {
        const Eigen::Isometry3d& B = config_.T_lidar_base;
        m.T_lidar0_lidar1 = B * (W0.inverse() * W1) * B.inverse();
        const double dist = m.T_lidar0_lidar1.translation().norm();
        const double turn = registration::rotation_angle(W0.inverse() * W1);
        const double st = config_.wheel_scale * dist + kWheelFloor;
        const double sr = config_.wheel_turn * turn + kTurnFloor;
        m.covariance.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() * st * st;
        m.covariance.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity() * sr * sr;
        m.has_translation = m.has_rotation = true;
    }
    Eigen::Matrix3d R_imu;
    if (integrate_gyro(t0, t1, &R_imu)) {
        const Eigen::Matrix3d& L = config_.T_lidar_imu.linear();
        m.T_lidar0_lidar1.linear() = L * R_imu * L.transpose();
        const double sr2 = config_.gyro_noise * config_.gyro_noise * dt +
                           config_.gyro_bias * config_.gyro_bias * dt * dt;
        m.covariance.bottomRightCorner<3, 3>() = Eigen::Matrix3d::Identity() * sr2;
        m.has_rotation = true;
    }
    if (!m.has_rotation) return std::nullopt;
    m.rate = registration::so3_log(m.T_lidar0_lidar1.linear()) / dt;
    return m;
}

Eigen::Isometry3d MotionPrior::predict(const Eigen::Isometry3d& T0, double t0, double t1,
                                       const Eigen::Isometry3d& fallback) const {
    const std::optional<PriorMotion> m = between(t0, t1);
    if (!m) return fallback;
    Eigen::Isometry3d delta = T0.inverse() * fallback;
    if (m->has_rotation) delta.linear() = m->T_lidar0_lidar1.linear();
    if (m->has_translation) delta.translation() = m->T_lidar0_lidar1.translation();
    return T0 * delta;
}

std::string MotionPrior::disagreement(const Eigen::Isometry3d& T0, double t0, double t1,
                                      const Eigen::Isometry3d& estimate) const {
    const std::optional<PriorMotion> m = between(t0, t1);
    if (!m) return "";
    const Eigen::Isometry3d fit = T0.inverse() * estimate;
    const double turn = registration::rotation_angle(
        Eigen::Isometry3d(m->T_lidar0_lidar1.linear().transpose() * fit.linear()));
    const double sr = std::sqrt(m->covariance.bottomRightCorner<3, 3>().diagonal().maxCoeff());
    const double max_turn =
        std::max(config_.gate_rotation * M_PI / 180.0, config_.gate_sigmas * sr);
    std::ostringstream s;
    s.precision(3);
    if (turn > max_turn) {
        s << "turned " << turn * 180.0 / M_PI << " deg off the motion prior's (at most "
          << max_turn * 180.0 / M_PI << ")";
        return s.str();
    }
    if (!m->has_translation) return "";
    const double moved = (fit.translation() - m->T_lidar0_lidar1.translation()).norm();
    const double st = std::sqrt(m->covariance.topLeftCorner<3, 3>().diagonal().maxCoeff());
    const double max_move = std::max(config_.gate_translation, config_.gate_sigmas * st);
    if (moved > max_move) {
        s << "moved " << moved << " m off the motion prior's (at most " << max_move << ")";
        return s.str();
    }
    return "";
}

void MotionPrior::deskew_velocity(const common::PointCloud& cloud,
                                  registration::Vector6d* velocity) const {
    if (!cloud.has_time() || !cloud.consistent()) return;
    const auto [lo, hi] = std::minmax_element(cloud.time.begin(), cloud.time.end());
    if (!std::isfinite(*lo) || !std::isfinite(*hi) || !(*hi - *lo > 1e-3)) return;
    const std::optional<PriorMotion> m = between(cloud.stamp + *lo, cloud.stamp + *hi);
    if (!m) return;
    const registration::Vector6d twist =
        registration::se3_log(m->T_lidar0_lidar1) / double(*hi - *lo);
    if (m->has_translation) velocity->head<3>() = twist.head<3>();
    if (m->has_rotation) velocity->tail<3>() = twist.tail<3>();
}

Eigen::Isometry3d MotionPrior::fill_unobserved(
    const Eigen::Isometry3d& T0, double t0, double t1, const Eigen::Isometry3d& estimate,
    const std::vector<registration::Vector6d>& directions, double lever) const {
    if (directions.empty() || !(lever > 0.0)) return estimate;
    const std::optional<PriorMotion> m = between(t0, t1);
    if (!m) return estimate;
    const Eigen::Isometry3d prior = T0 * m->T_lidar0_lidar1;
    // Both motions in odometry axes, rotation as displacement at the lever arm (as the
    // degenerate directions are); what the prior did not measure is taken from the fit.
    const auto motion = [&T0, lever](const Eigen::Isometry3d& T) {
        registration::Vector6d v;
        v.head<3>() = T.translation() - T0.translation();
        v.tail<3>() = lever * registration::so3_log(T.linear() * T0.linear().transpose());
        return v;
    };
    const registration::Vector6d fit = motion(estimate);
    registration::Vector6d wanted = motion(prior);
    if (!m->has_translation) wanted.head<3>() = fit.head<3>();
    if (!m->has_rotation) wanted.tail<3>() = fit.tail<3>();
    registration::Vector6d out = fit;
    for (const registration::Vector6d& v : directions) out += v.dot(wanted - fit) * v;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = registration::so3_exp(out.tail<3>() / lever) * T0.linear();
    T.translation() = T0.translation() + out.head<3>();
    return T;
}

void MotionPrior::observe(double stamp, const Eigen::Matrix3d& R_odom_lidar, bool registered) {
    if (config_.bias_gain <= 0.0 || !registered || imu_.empty()) {
        window_open_ = false;
        return;
    }
    if (window_open_ && stamp - window_stamp_ >= config_.bias_window) {
        Eigen::Matrix3d R_gyro;
        if (integrate_gyro(window_stamp_, stamp, &R_gyro)) {
            const Eigen::Matrix3d& L = config_.T_lidar_imu.linear();
            // The fit's turn over the window, in the IMU frame.
            const Eigen::Matrix3d R_fit =
                L.transpose() * window_rotation_.transpose() * R_odom_lidar * L;
            // Integrated with a bias too small by e, the gyro turns further by e T than the fit.
            const Eigen::Vector3d excess =
                registration::so3_log(R_fit.transpose() * R_gyro) / (stamp - window_stamp_);
            const double bound = 3.0 * config_.gyro_bias;
            bias_ = (bias_ + config_.bias_gain * excess).cwiseMax(-bound).cwiseMin(bound);
        }
        window_open_ = false;
    }
    if (!window_open_) {
        window_open_ = true;
        window_stamp_ = stamp;
        window_rotation_ = R_odom_lidar;
    }
}

}  // namespace ltm::odometry
