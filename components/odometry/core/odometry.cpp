#include "odometry/core/odometry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace ltm::odometry {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;
constexpr double kUnknownVariance = 1e4;  // covariance diagonal of a pose that is not estimated

// The coarse stage: the same registration with distances scaled to the coarse voxels.
RegistrationConfig coarse_config(const OdometryConfig& config) {
    RegistrationConfig c = config.registration;
    const double f = std::max(1, config.coarse_voxel_factor);
    c.max_correspondence_distance *= f;
    c.kernel_scale *= f;
    c.convergence_translation *= f;
    c.convergence_rotation *= f;
    return c;
}

const OdometryConfig& checked(const OdometryConfig& config) {
    common::throw_if(validate(config), "odometry");
    return config;
}

}  // namespace

const char* to_string(FrameStatus status) {
    switch (status) {
        case FrameStatus::kInitialised:
            return "initialised";
        case FrameStatus::kTracked:
            return "tracked";
        case FrameStatus::kSkippedTooFewPoints:
            return "skipped (too few points)";
        case FrameStatus::kRejectedStamp:
            return "rejected (bad stamp)";
        case FrameStatus::kDiverged:
            return "diverged";
    }
    return "unknown";
}

Odometry::Odometry(const OdometryConfig& config, const Eigen::Isometry3d& T_odom_lidar_initial)
    : config_(checked(config)),
      initial_pose_(T_odom_lidar_initial),
      parallel_(config.threads),
      preprocessor_(config.preprocess, config.voxel_size),
      registration_(config.registration, config.voxel_size, &parallel_),
      coarse_registration_(coarse_config(config),
                           config.voxel_size * std::max(1, config.coarse_voxel_factor), &parallel_),
      motion_(config.prediction == "frame"  ? PredictionMode::kFrame
              : config.prediction == "none" ? PredictionMode::kNone
                                            : PredictionMode::kTime),
      maps_(config),
      keyframes_(config.keyframe) {}

FrameResult Odometry::reject(FrameResult result, FrameStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    result.covariance = registration::Matrix6d::Identity() * kUnknownVariance;
    return result;
}

FrameResult Odometry::register_frame(const common::PointCloud& cloud) {
    FrameResult r;
    r.stamp = cloud.stamp;
    r.input_points = cloud.size();
    r.T_odom_lidar = motion_.poses() ? motion_.last_pose() : initial_pose_;
    if (!maps_.empty()) r.local_map_id = maps_.current().id();
    if (!std::isfinite(cloud.stamp)) {
        return reject(r, FrameStatus::kRejectedStamp, "scan stamp is not finite");
    }
    if (has_stamp_ && !(cloud.stamp > last_stamp_)) {
        std::ostringstream s;
        s.precision(17);
        s << "time went backwards: scan stamp " << cloud.stamp << " is not after the previous "
          << last_stamp_;
        return reject(r, FrameStatus::kRejectedStamp, s.str());
    }

    const registration::Vector6d velocity = motion_.velocity();
    auto tick = std::chrono::steady_clock::now();
    auto lap = [&tick]() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - tick).count();
        tick = now;
        return ms;
    };
    preprocessor_.run(cloud, motion_.poses() == 2 ? &velocity : nullptr, &scan_);
    r.preprocess_ms = lap();
    r.dropped_non_finite = scan_.dropped_non_finite;
    r.dropped_range = scan_.dropped_range;
    r.map_points = scan_.map_points.size();
    r.registration_points = scan_.registration_points.size();
    r.deskewed = scan_.deskewed;
    const Eigen::Isometry3d predicted =
        motion_.poses() ? motion_.predict(cloud.stamp) : initial_pose_;
    r.T_odom_lidar = predicted;

    if (scan_.registration_points.size() < std::size_t(config_.min_scan_points)) {
        std::ostringstream s;
        s << "scan skipped: " << scan_.registration_points.size() << " usable points of "
          << cloud.size() << " (" << scan_.dropped_non_finite << " non-finite), fewer than "
          << config_.min_scan_points << "; prediction carried forward";
        r = reject(r, FrameStatus::kSkippedTooFewPoints, s.str());
        has_stamp_ = true;
        last_stamp_ = cloud.stamp;
        if (motion_.poses()) motion_.push(cloud.stamp, predicted);
        return r;
    }

    if (maps_.empty()) {
        r.status = FrameStatus::kInitialised;
        r.covariance.setZero();  // the first pose defines the odometry frame
    } else {
        // First from the prediction. When that fails, or looks doubtful (not converged, or a
        // residual well above the recent ones), once more from the last pose, keeping the better
        // result: a wrong velocity must not pull the odometry away from the map.
        FrameResult attempt = r;
        std::string why = try_register(predicted, &attempt);
        int attempts = 1;
        const bool doubtful =
            why.empty() &&
            (!attempt.converged ||
             (typical_rms_ > 0.0 &&
              attempt.residual_rms > config_.divergence.retry_residual_ratio * typical_rms_));
        const Eigen::Isometry3d& last = motion_.last_pose();
        const Eigen::Isometry3d jump = last.inverse() * predicted;
        if ((!why.empty() || doubtful) && motion_.poses() == 2 &&
            (jump.translation().norm() > 0.01 ||
             registration::rotation_angle(jump) > 0.1 / kRadToDeg)) {
            FrameResult second = r;
            const std::string retry = try_register(last, &second);
            attempts = 2;
            if (retry.empty() && (!why.empty() || second.residual_rms < attempt.residual_rms)) {
                attempt = second;
                why.clear();
            } else if (!why.empty()) {
                why += "; from the last pose: " + retry;
            }
        }
        r = attempt;
        r.attempts = attempts;
        r.registration_ms = lap();
        if (!why.empty()) {
            r.T_odom_lidar = predicted;
            r = reject(r, FrameStatus::kDiverged, why + "; prediction carried forward");
            has_stamp_ = true;
            last_stamp_ = cloud.stamp;
            motion_.push(cloud.stamp, predicted);
            return r;
        }
        r.status = FrameStatus::kTracked;
        typical_rms_ =
            typical_rms_ > 0.0 ? 0.9 * typical_rms_ + 0.1 * r.residual_rms : r.residual_rms;
    }
    // The map gets the scan de-skewed with the motion just estimated (better than the predicted
    // one, and available from the second scan on).
    if (motion_.poses() > 0 && cloud.stamp > motion_.last_stamp()) {
        const registration::Vector6d estimated =
            registration::se3_log(motion_.last_pose().inverse() * r.T_odom_lidar) /
            (cloud.stamp - motion_.last_stamp());
        preprocessor_.redeskew_map_points(estimated, &scan_);
        r.deskewed = scan_.deskewed;
    }
    accept(r);
    lap();
    r.new_local_map = maps_.integrate(scan_.map_points, r.T_odom_lidar, cloud.stamp);
    r.local_map_id = maps_.current().id();
    if (keyframes_.check(r.T_odom_lidar)) {
        Keyframe k;
        k.id = next_keyframe_id_++;
        k.stamp = cloud.stamp;
        k.T_odom_lidar = r.T_odom_lidar;
        k.local_map_id = r.local_map_id;
        k.points = scan_.map_points;
        r.keyframe = std::move(k);
    }
    r.update_ms = lap();
    return r;
}

std::string Odometry::try_register(const Eigen::Isometry3d& guess_odom, FrameResult* r) {
    const LocalMap& map = maps_.current();
    const Eigen::Isometry3d T_odom_map = map.T_odom_map();
    Eigen::Isometry3d guess = T_odom_map.inverse() * guess_odom;
    r->coarse_iterations = 0;
    if (map.coarse() != nullptr) {
        // Every other point is plenty for the coarse stage (it only has to reach the basin).
        coarse_points_.clear();
        for (std::size_t i = 0; i < scan_.registration_points.size(); i += 2) {
            coarse_points_.push_back(scan_.registration_points[i]);
        }
        const registration::RegistrationResult coarse =
            coarse_registration_.align(coarse_points_, *map.coarse(), guess);
        r->coarse_iterations = coarse.iterations;
        if (coarse.ok()) guess = coarse.T_map_lidar;
    }
    const registration::RegistrationResult reg =
        registration_.align(scan_.registration_points, map.voxels(), guess);
    r->iterations = reg.iterations;
    r->correspondences = reg.correspondences;
    r->residual_rms = reg.residual_rms;
    r->converged = reg.status == registration::RegistrationResult::Status::kConverged;
    const Eigen::Isometry3d estimate = T_odom_map * reg.T_map_lidar;
    const Eigen::Isometry3d correction = guess_odom.inverse() * estimate;
    const double dt = correction.translation().norm();
    const double dr = registration::rotation_angle(correction) * kRadToDeg;
    const DivergenceConfig& d = config_.divergence;
    std::ostringstream why;
    if (!reg.ok()) {
        why << "registration failed: " << to_string(reg.status) << " (" << reg.correspondences
            << " correspondences)";
    } else if (!estimate.matrix().allFinite()) {
        why << "registration produced a non-finite pose";
    } else if (dt > d.max_translation_correction || dr > d.max_rotation_correction) {
        why << "registration moved " << dt << " m / " << dr
            << " deg from its initial guess (limits " << d.max_translation_correction << " m / "
            << d.max_rotation_correction << " deg)";
    } else if (!r->converged && (reg.last_step_translation > d.max_final_step_translation ||
                                 reg.last_step_rotation * kRadToDeg > d.max_final_step_rotation)) {
        why << "registration did not converge in " << reg.iterations << " iterations (last step "
            << reg.last_step_translation << " m / " << reg.last_step_rotation * kRadToDeg
            << " deg)";
    }
    if (why.str().empty()) {
        r->T_odom_lidar = estimate;
        r->covariance = reg.covariance;
        r->degenerate_directions = reg.degenerate_directions;
        r->min_information = reg.min_information;
    }
    return why.str();
}

void Odometry::accept(const FrameResult& result) {
    has_stamp_ = true;
    last_stamp_ = result.stamp;
    motion_.push(result.stamp, result.T_odom_lidar);
}

void Odometry::finish_local_maps() { maps_.finish_all(); }

}  // namespace ltm::odometry
