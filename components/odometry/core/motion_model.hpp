#pragma once
// Constant-velocity prediction (METHOD.md section 2): T_pred = T_{i-1} (T_{i-2}^-1
// T_{i-1})^(dt/dt'), the last relative motion scaled to the time since the last frame (or once per
// frame).
#include <Eigen/Geometry>
#include <vector>

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

    // T_stamp_mid: the LiDAR at the middle of the sweep in the frame at the stamp, as the scan
    // was de-skewed (registration::PreprocessedScan; identity for scans taken at their stamp).
    void push(double stamp, const Eigen::Isometry3d& T_odom_lidar,
              const Eigen::Isometry3d& T_stamp_mid = Eigen::Isometry3d::Identity());
    // The pose at `stamp` (identity before the first pose, the last pose with only one).
    Eigen::Isometry3d predict(double stamp) const;
    // The same holding the last heading: the last step's translation in odometry axes scaled to
    // the time (not turned with the turn rate), the last pose's rotation.
    Eigen::Isometry3d predict_heading_held(double stamp) const;
    // Body-frame twist per second [v; w] between the last two poses (zero with fewer), taken at
    // the middle of their sweeps: that is where registration fixes a de-skewed scan, whatever the
    // velocity it was de-skewed with. Between the poses at the stamps, which move with that
    // velocity's error, each error would come back into the next velocity with the opposite sign.
    registration::Vector6d velocity() const;
    // The same from the last pose to the mid-sweep pose of a scan at `stamp` (zero without a last
    // pose or a later stamp).
    registration::Vector6d velocity_to(double stamp, const Eigen::Isometry3d& T_odom_mid) const;
    // The last registration could not observe `directions` (unit, [dt; dr * lever] in odometry
    // axes, as RegistrationResult::degenerate_directions): the last motion along them is not a
    // measurement but the prediction carried on. Keep only `keep` of it, so that a wrong velocity
    // along an unobservable direction dies out instead of being extrapolated for ever. A direction
    // within ~26 deg of the last step's (the way the sensor travels: down a corridor, a tunnel)
    // keeps `travel_keep` of it instead: a vehicle goes on at its speed, while a sideways velocity
    // a narrow view over open ground made up still dies out. A last step turning more than
    // `travel_turn` [rad] is no travel (a robot turning on the spot): `keep` everywhere.
    void damp(const std::vector<registration::Vector6d>& directions, double lever, double keep,
              double travel_keep, double travel_turn);

  private:
    PredictionMode mode_;
    int count_ = 0;
    double stamp_[2] = {0.0, 0.0};
    Eigen::Isometry3d pose_[2] = {Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity()};
    Eigen::Isometry3d stamp_mid_[2] = {Eigen::Isometry3d::Identity(),
                                       Eigen::Isometry3d::Identity()};
};

}  // namespace ltm::odometry
