#pragma once
// Keyframe selection: the first pose, then every `distance` metres or `angle` degrees.
#include <Eigen/Geometry>

#include "odometry/core/odometry_config.hpp"

namespace ltm::odometry {

class KeyframeSelector {
  public:
    explicit KeyframeSelector(const KeyframeConfig& config) : config_(config) {}
    // True (and remembers the pose) when T is a keyframe.
    bool check(const Eigen::Isometry3d& T_odom_lidar);
    void reset() { has_last_ = false; }

  private:
    KeyframeConfig config_;
    bool has_last_ = false;
    Eigen::Isometry3d last_ = Eigen::Isometry3d::Identity();
};

}  // namespace ltm::odometry
