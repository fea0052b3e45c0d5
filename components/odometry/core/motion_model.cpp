#include "odometry/core/motion_model.hpp"

#include <cmath>

namespace ltm::odometry {
namespace {

constexpr double kTravelCos = 0.9;  // a degenerate direction this close to the last step's: travel

// Re-orthonormalised: Isometry3d::inverse() transposes the rotation, so a rotation that drifts
// from orthonormal would make repeated extrapolation grow without bound.
Eigen::Isometry3d normalised(const Eigen::Isometry3d& T) {
    Eigen::Isometry3d out = T;
    out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
    return out;
}

}  // namespace

void MotionModel::push(double stamp, const Eigen::Isometry3d& T_odom_lidar,
                       const Eigen::Isometry3d& T_stamp_mid) {
    stamp_[0] = stamp_[1];
    pose_[0] = pose_[1];
    stamp_mid_[0] = stamp_mid_[1];
    stamp_[1] = stamp;
    pose_[1] = normalised(T_odom_lidar);
    stamp_mid_[1] = normalised(T_stamp_mid);
    if (count_ < 2) ++count_;
}

Eigen::Isometry3d MotionModel::predict(double stamp) const {
    if (count_ == 0) return Eigen::Isometry3d::Identity();
    if (count_ == 1 || mode_ == PredictionMode::kNone) return pose_[1];
    const Eigen::Isometry3d delta = pose_[0].inverse() * pose_[1];
    if (mode_ == PredictionMode::kFrame) return normalised(pose_[1] * delta);
    const double dt_prev = stamp_[1] - stamp_[0];
    const double dt = stamp - stamp_[1];
    if (!(dt_prev > 0.0) || !(dt >= 0.0)) return pose_[1];
    return normalised(pose_[1] * registration::scale_motion(delta, dt / dt_prev));
}

Eigen::Isometry3d MotionModel::predict_heading_held(double stamp) const {
    Eigen::Isometry3d out = predict(stamp);
    if (count_ < 2 || mode_ == PredictionMode::kNone) return out;
    const double dt_prev = stamp_[1] - stamp_[0];
    const double dt = stamp - stamp_[1];
    const double scale = mode_ == PredictionMode::kFrame ? 1.0
                         : (dt_prev > 0.0 && dt >= 0.0)  ? dt / dt_prev
                                                         : 0.0;
    out.linear() = pose_[1].linear();
    out.translation() =
        pose_[1].translation() + scale * (pose_[1].translation() - pose_[0].translation());
    return out;
}

void MotionModel::damp(const std::vector<registration::Vector6d>& directions, double lever,
                       double keep, double travel_keep, double travel_turn) {
    if (count_ < 2 || directions.empty()) return;
    // The last motion in odometry axes, rotation as displacement at the lever arm.
    registration::Vector6d m;
    m.head<3>() = pose_[1].translation() - pose_[0].translation();
    m.tail<3>() = lever * registration::so3_log(pose_[1].linear() * pose_[0].linear().transpose());
    const Eigen::Vector3d step = m.head<3>();
    // Turning more than travel_turn a step is not travelling down a corridor (a robot turning on
    // the spot, whose last walk must not be carried through the spin): no direction is travel.
    const bool straight = m.tail<3>().norm() <= lever * travel_turn;
    for (const registration::Vector6d& v : directions) {
        const Eigen::Vector3d t = v.head<3>();
        const bool travel = straight && step.norm() > 1e-6 && t.norm() > 0.9 &&
                            std::abs(t.dot(step)) > kTravelCos * t.norm() * step.norm();
        m -= (1.0 - (travel ? travel_keep : keep)) * v.dot(m) * v;
    }
    // The previous pose is rewritten so that the last motion is the damped one.
    pose_[0].linear() = registration::so3_exp(-m.tail<3>() / lever) * pose_[1].linear();
    pose_[0].translation() = pose_[1].translation() - m.head<3>();
    pose_[0] = normalised(pose_[0]);
}

registration::Vector6d MotionModel::velocity() const {
    const double dt_prev = stamp_[1] - stamp_[0];
    if (count_ < 2 || !(dt_prev > 0.0)) return registration::Vector6d::Zero();
    return registration::se3_log((pose_[0] * stamp_mid_[0]).inverse() * pose_[1] * stamp_mid_[1]) /
           dt_prev;
}

registration::Vector6d MotionModel::velocity_to(double stamp,
                                                const Eigen::Isometry3d& T_odom_mid) const {
    const double dt = stamp - stamp_[1];
    if (count_ < 1 || !(dt > 0.0)) return registration::Vector6d::Zero();
    return registration::se3_log((pose_[1] * stamp_mid_[1]).inverse() * normalised(T_odom_mid)) /
           dt;
}

}  // namespace ltm::odometry
