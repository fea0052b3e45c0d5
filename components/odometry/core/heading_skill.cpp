#include "odometry/core/heading_skill.hpp"

#include <cmath>

namespace ltm::odometry {
namespace {
constexpr double kGain = 0.25;  // running mean over about the last 7 scans
}

void HeadingSkill::observe(double extrapolated_error, double held_error) {
    if (!std::isfinite(extrapolated_error) || !std::isfinite(held_error)) return;
    const double g = scans_ == 0 ? 1.0 : kGain;
    extrapolated_ += g * (extrapolated_error - extrapolated_);
    held_ += g * (held_error - held_);
    ++scans_;
}

bool HeadingSkill::hold() const {
    return ratio_ > 0.0 && scans_ >= kMinScans && held_ <= ratio_ * extrapolated_;
}

}  // namespace ltm::odometry
