#pragma once
// Constant-velocity prediction (METHOD.md section 2): T_pred = T_{i-1} (T_{i-2}^-1
// T_{i-1})^(dt/dt'), the last relative motion scaled to the time since the last frame (or once per
// frame).
#include <Eigen/Geometry>

#include "registration/core/se3.hpp"

namespace ltm::odometry {

enum class PredictionMode {
    kTime,   // the last motion scaled by the time since the last frame (streams at a steady rate)
    kFrame,  // the last motion once per frame (irregular stamps, e.g. keyframe streams)
    kNone,   // the last pose
};

class MotionModel {
  public:
    explicit MotionModel(PredictionMode mode = PredictionMode::kTime) : mode_(mode) {}
    void reset() { count_ = 0; }
    int poses() const { return count_; }  // 0, 1 or 2 (the last two are kept)
    double last_stamp() const { return stamp_[1]; }
    const Eigen::Isometry3d& last_pose() const { return pose_[1]; }

    void push(double stamp, const Eigen::Isometry3d& T_odom_lidar);
    // The pose at `stamp` (identity before the first pose, the last pose with only one).
    Eigen::Isometry3d predict(double stamp) const;
    // Body-frame twist per second [v; w] between the last two poses (zero with fewer).
    registration::Vector6d velocity() const;

  private:
    PredictionMode mode_;
    int count_ = 0;
    double stamp_[2] = {0.0, 0.0};
    Eigen::Isometry3d pose_[2] = {Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity()};
};

}  // namespace ltm::odometry
