#include "odometry/core/keyframe_selector.hpp"

#include <cmath>

#include "registration/core/se3.hpp"

namespace ltm::odometry {

bool KeyframeSelector::check(const Eigen::Isometry3d& T) {
    if (has_last_) {
        const Eigen::Isometry3d delta = last_.inverse() * T;
        const bool far = delta.translation().norm() >= config_.distance;
        const bool turned = registration::rotation_angle(delta) * 180.0 / M_PI >= config_.angle;
        if (!far && !turned) return false;
    }
    has_last_ = true;
    last_ = T;
    return true;
}

}  // namespace ltm::odometry
