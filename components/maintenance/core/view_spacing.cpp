#include "maintenance/core/view_spacing.hpp"

#include <cmath>

namespace ltm::maintenance {

std::optional<std::string> validate(const ViewSpacingConfig& c) {
    if (!(c.distance >= 0.0)) return std::string("view_distance: must be >= 0 (0: every scan)");
    if (!(c.angle_deg > 0.0)) return std::string("view_angle: must be > 0 [deg]");
    if (!(c.interval_s > 0.0)) return std::string("view_interval_s: must be > 0 [s]");
    return std::nullopt;
}

bool ViewSpacing::take(double stamp, const Eigen::Isometry3d& T_world_sensor) {
    // Within 5 % of each bound: steps of a steady drive (0.2 m at 2 m/s and 10 Hz) sum to 0.4 m
    // +- a little, and a bound met only on one side of that would take every third scan.
    constexpr double kSlack = 0.95;
    bool take = config_.distance <= 0.0 || !has_last_ || stamp < last_stamp_ ||
                stamp - last_stamp_ >= kSlack * config_.interval_s;
    if (!take) {
        const Eigen::Isometry3d d = last_pose_.inverse() * T_world_sensor;
        const double angle = Eigen::AngleAxisd(d.linear()).angle() * 180.0 / M_PI;
        take = d.translation().norm() >= kSlack * config_.distance ||
               angle >= kSlack * config_.angle_deg;
    }
    if (!take) {
        ++left_out_;
        return false;
    }
    has_last_ = true;
    last_stamp_ = stamp;
    last_pose_ = T_world_sensor;
    ++taken_;
    return true;
}

}  // namespace ltm::maintenance
