#include "odometry/core/odometry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace ltm::odometry {

// Tracked frames whose fit is the yardstick of a young map (early_*).
constexpr int kEarlyFrames = 10;
namespace {

// Whether a fit's Hessian constrains a translation direction more than 30 deg from the vertical.
bool fixes_a_horizontal_direction(const registration::Matrix6d& information,
                                  const ObservabilityConfig& config) {
    const Observability o = translation_observability(information, config.weak_information);
    for (int k = 3 - o.constrained; k < 3; ++k) {
        if (std::abs(o.directions.col(k).z()) < std::cos(30.0 * M_PI / 180.0)) return true;
    }
    return false;
}

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

// A search guess is only probed: a few coarse iterations on a quarter of the points, enough to
// rank the guesses; the best go on to the full coarse and fine stages.
RegistrationConfig probe_config(const OdometryConfig& config) {
    RegistrationConfig c = coarse_config(config);
    c.max_iterations = std::min(c.max_iterations, 8);
    return c;
}

// How many of a registration's degenerate directions ([dt; dr * lever], unit) are mostly a
// translation: the position along them is the prediction's.
int translation_directions(const std::vector<registration::Vector6d>& directions) {
    int n = 0;
    for (const registration::Vector6d& v : directions) n += v.head<3>().norm() > 0.7 ? 1 : 0;
    return n;
}

// The fit's position along its unobserved translation directions (odometry axes) moved back to
// the prediction's.
void keep_unobserved_at(const Eigen::Isometry3d& predicted, FrameResult* r) {
    hold_along(predicted.translation(), translation_parts(r->degenerate_directions),
               &r->T_odom_lidar);
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
        case FrameStatus::kRecovered:
            return "recovered";
        case FrameStatus::kRestarted:
            return "restarted";
        case FrameStatus::kDegenerate:
            return "degenerate";
        case FrameStatus::kLost:
            return "lost";
        case FrameStatus::kSkippedTooFewPoints:
            return "skipped (too few points)";
        case FrameStatus::kRejectedStamp:
            return "rejected (bad stamp)";
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
      probe_registration_(probe_config(config),
                          config.voxel_size * std::max(1, config.coarse_voxel_factor), &parallel_),
      motion_(config.prediction == "frame"  ? PredictionMode::kFrame
              : config.prediction == "none" ? PredictionMode::kNone
                                            : PredictionMode::kTime),
      maps_(config),
      keyframes_(config.keyframe),
      heading_(config.tracking.heading_hold_ratio) {}

FrameResult Odometry::reject(FrameResult result, FrameStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    result.covariance = registration::Matrix6d::Identity() * kUnknownVariance;
    return result;
}

FrameResult Odometry::register_frame(const common::PointCloud& cloud) {
    FrameResult r;
    bool kept_out = false;  // degenerate by the observability check: stays out of the map
    r.stamp = cloud.stamp;
    r.input_points = cloud.size();
    r.T_odom_lidar = motion_.poses() ? motion_.last_pose() : initial_pose_;
    if (!maps_.empty()) r.local_map_id = maps_.current().id();
    if (stamp_refused(cloud, &r)) return r;
    // The interval since the last scan, against the stream's own cadence.
    const double gap = has_stamp_ ? cloud.stamp - last_stamp_ : 0.0;
    const bool gap_break = has_stamp_ && cadence_.is_break(gap, config_.tracking.restart_gap,
                                                           config_.tracking.restart_gap_cadence);
    const double usual_interval = cadence_.usual();  // for the message, before this interval
    if (has_stamp_) cadence_.add(gap);

    registration::Vector6d velocity = motion_.velocity();
    if (prior_ != nullptr) prior_->deskew_velocity(cloud, &velocity);
    auto tick = std::chrono::steady_clock::now();
    auto lap = [&tick]() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - tick).count();
        tick = now;
        return ms;
    };
    preprocessor_.run(cloud, motion_.poses() == 2 ? &velocity : nullptr, &scan_);
    // Every other point is plenty for the coarse stage (it only has to reach the basin).
    coarse_points_.clear();
    for (std::size_t i = 0; i < scan_.registration_points.size(); i += 2) {
        coarse_points_.push_back(scan_.registration_points[i]);
    }
    r.preprocess_ms = lap();
    r.dropped_non_finite = scan_.dropped_non_finite;
    r.dropped_range = scan_.dropped_range;
    r.map_points = scan_.map_points.size();
    r.registration_points = scan_.registration_points.size();
    r.deskewed = scan_.deskewed;
    Eigen::Isometry3d predicted = motion_.poses() ? motion_.predict(cloud.stamp) : initial_pose_;
    // A sparse stream (scans further apart than tracking.search_after) whose turns the constant
    // turn rate has predicted worse than the held heading: the heading is held (heading_skill.hpp).
    const Eigen::Isometry3d extrapolated = predicted;
    const bool far_apart =
        motion_.poses() >= 1 && cloud.stamp - motion_.last_stamp() > config_.tracking.search_after;
    const bool sparse = far_apart && motion_.poses() >= 2;
    if (sparse && heading_.hold()) {
        predicted = motion_.predict_heading_held(cloud.stamp);
        r.heading_held = true;
    }
    if (prior_ != nullptr && motion_.poses() > 0)
        predicted =
            prior_->predict(motion_.last_pose(), motion_.last_stamp(), cloud.stamp, predicted);
    r.T_odom_lidar = predicted;

    r.segment = maps_.segment();
    const double since_tracked = cloud.stamp - last_tracked_stamp_;
    if (scan_.registration_points.size() < std::size_t(config_.min_scan_points)) {
        std::ostringstream s;
        s << "scan skipped: " << scan_.registration_points.size() << " usable points of "
          << cloud.size() << " (" << scan_.dropped_non_finite << " non-finite), fewer than "
          << config_.min_scan_points << "; prediction carried forward";
        r = reject(r, FrameStatus::kSkippedTooFewPoints, s.str());
        has_stamp_ = true;
        last_stamp_ = cloud.stamp;
        if (motion_.poses()) motion_.push(cloud.stamp, predicted, scan_.T_stamp_mid);
        if (!maps_.empty()) {
            lost_ = true;
            r.lost_for = since_tracked;
        }
        return r;
    }

    if (maps_.empty()) {
        r.status = FrameStatus::kInitialised;
        r.covariance.setZero();  // the first pose defines the odometry frame
    } else if (gap_break) {
        // No scan for a while: whatever happened meanwhile (the robot carried, a long stop of the
        // sensor) the motion model cannot bridge, and a fit of this scan to the old map can be a
        // look-alike place (a repetitive yard). A new segment, joined later by a loop or the
        // localisation. Judged against the stream's cadence: a keyframe stream pauses while the
        // robot stands (scan_cadence.hpp).
        std::ostringstream s;
        s << "a gap of " << gap << " s between scans (more than tracking.restart_gap "
          << config_.tracking.restart_gap << " s";
        if (config_.tracking.restart_gap_cadence > 0.0)
            s << " and " << config_.tracking.restart_gap_cadence << " x the usual "
              << usual_interval << " s";
        s << ": the robot may have been moved)";
        restart_segment(s.str(), predicted, since_tracked, &r);
    } else {
        // From the prediction first. When that is refused or doubtful, a search from other
        // guesses (the last pose, the prediction turned about its z axis); the better fit wins.
        FrameResult attempt = r;
        std::string why = try_register(predicted, since_tracked, &attempt);
        int attempts = 1;
        if (!why.empty() || doubtful(attempt) ||
            (since_tracked > config_.tracking.search_after && !excellent(attempt))) {
            FrameResult found = r;
            const std::string not_found = search(predicted, since_tracked, &found);
            attempts += found.attempts;
            if (not_found.empty() && (!why.empty() || found.inliers > attempt.inliers)) {
                attempt = found;
                why.clear();
            } else if (!why.empty()) {
                why += "; search: " + not_found;
            }
            attempt.searched = true;
        }
        if (attempt.searched && why.empty()) attempt.search_used = "search";
        r = attempt;
        r.attempts = attempts;
        const bool observable = !why.empty() || check_observability(predicted, since_tracked, &r);
        kept_out = !observable;
        r.registration_ms = lap();
        if (!why.empty() && since_tracked < config_.tracking.restart_after) {
            std::ostringstream s;
            s << why << "; lost for " << since_tracked << " s, prediction carried forward";
            r.T_odom_lidar = predicted;
            r = reject(r, FrameStatus::kLost, s.str());
            r.lost_for = since_tracked;
            lost_ = true;
            has_stamp_ = true;
            last_stamp_ = cloud.stamp;
            motion_.push(cloud.stamp, predicted, scan_.T_stamp_mid);
            return r;
        }
        // A run of degenerate scans kept out of the map whose fits fix no horizontal direction
        // (every direction they constrain is within 30 deg of the vertical: the ground's normal):
        // the map holds nothing around the robot but ground. It is behind the robot, which went
        // on across open ground at a speed nothing measured; fits to it say nothing more. (A
        // corridor's walls fix the position across it and the heading: that map is kept.)
        const bool ground_only =
            kept_out && !fixes_a_horizontal_direction(r.information, config_.observability);
        kept_out_run_ = ground_only && segment_scans_ >= kYoungSegmentScans ? kept_out_run_ + 1 : 0;
        const bool map_behind = why.empty() && config_.tracking.restart_kept_out > 0 &&
                                kept_out_run_ >= config_.tracking.restart_kept_out;
        if (!why.empty()) {
            std::ostringstream s;
            s << "lost for " << since_tracked << " s (" << why << ")";
            restart_segment(s.str(), predicted, since_tracked, &r);
        } else if (map_behind) {
            std::ostringstream s;
            s << kept_out_run_ << " degenerate scans in a row kept out of the map, their fits "
              << "fixing no horizontal direction (tracking.restart_kept_out "
              << config_.tracking.restart_kept_out << "): the map is behind the robot";
            restart_segment(s.str(), predicted, since_tracked, &r);
            kept_out = false;
        } else {
            // A direction of the translation the registration could not observe (below
            // registration.degeneracy_ratio: solution remapping left it at the prediction) makes
            // the position along it the motion model's: degenerate, never "tracked".
            const int unobserved = translation_directions(r.degenerate_directions);
            // Where the registration could not observe, the position is the prediction's: the
            // start of the last registration may have slid there (a search guess's coarse probe,
            // the early iterations before the direction went flat: hku-avia session 2 every 5th
            // keyframe, 20-27 m along a direction the fit reported unobserved). Only on a sparse
            // stream: at the sensor's rate the fit starts at the prediction and stays near it.
            if (unobserved > 0 && far_apart) keep_unobserved_at(predicted, &r);
            r.status = !observable || unobserved > 0 ? FrameStatus::kDegenerate
                       : lost_                       ? FrameStatus::kRecovered
                                                     : FrameStatus::kTracked;
            if (observable && unobserved > 0) {
                std::ostringstream s;
                s.precision(3);
                s << "degenerate: the registration could not observe " << unobserved
                  << " translation direction(s) (information " << r.min_information
                  << " below registration.degeneracy_ratio "
                  << config_.registration.degeneracy_ratio
                  << "): the position along it is the motion model's";
                r.message = s.str();
            } else if (!observable) {
                std::ostringstream s;
                s.precision(3);
                s << "degenerate: " << r.constrained_directions
                  << " of 3 translation directions constrained (information "
                  << r.translation_information[0] << "), the search along the weakest "
                  << (std::string(r.search_used) == "along (fit kept, weak)"
                          ? "peaked where the fit from there was no better"
                          : "found no distinct fit")
                  << " (contrast " << r.profile_contrast << "): the position along it is the "
                  << (std::string(r.search_used) == "motion model" ? "motion model's"
                                                                   : "fit's (weakly constrained)");
                r.message = s.str();
            } else if (lost_) {
                std::ostringstream s;
                s << "recovered after " << since_tracked << " s lost";
                r.message = s.str();
                r.lost_for = since_tracked;
            }
            // The turn this scan measured: only from the last scan at most tracking.search_after
            // before (further apart the fit's rotation may be a yaw-search guess: a weak road's
            // first step fitted 47 deg turned, Observability.LargeSteps...) and by a fit whose
            // registration observed the rotation about the turn's axis (the ground alone cannot
            // see a turn about the vertical: FieldStart's yard fits turned up to 60 deg a scan).
            const double step_dt = cloud.stamp - motion_.last_stamp();
            const Eigen::Vector3d turn = registration::so3_log(
                r.T_odom_lidar.linear() * motion_.last_pose().linear().transpose());
            r.turn_measured =
                step_dt > 0.0 && step_dt <= config_.tracking.search_after &&
                !turn_unobserved(r.degenerate_directions,
                                 turn.norm() > 1e-6 ? Eigen::Vector3d(turn.normalized())
                                                    : Eigen::Vector3d(Eigen::Vector3d::UnitZ()));
            // A scan that cannot measure its turn goes by the recent rate, which fades over
            // tracking.spin_window while nothing measures it.
            r.turn_rate = recent_turn_.rate();
            if (r.turn_measured) {
                r.turn_rate =
                    std::max(r.turn_rate, turn_rate(motion_.last_pose(), r.T_odom_lidar, step_dt));
            }
            if (r.status == FrameStatus::kDegenerate) hold_while_spinning(kept_out, &r);
            inflate_covariance(predicted, since_tracked, &r);
            learn(r);
        }
        lost_ = false;
    }
    // The prior where unobserved (a scan degenerate only where the registration could not observe
    // is a fit everywhere else).
    if (prior_ != nullptr &&
        (r.registered() || (r.status == FrameStatus::kDegenerate && !kept_out)) &&
        motion_.poses() > 0) {
        r.T_odom_lidar = prior_->fill_unobserved(
            motion_.last_pose(), motion_.last_stamp(), cloud.stamp, r.T_odom_lidar,
            r.degenerate_directions, config_.registration.degeneracy_length);
    }
    // The map gets the scan de-skewed with the motion just estimated (better than the predicted
    // one, and available from the second scan on). Registration fixed the pose at the middle of
    // the sweep; the pose at the stamp follows with that motion.
    if (motion_.poses() > 0 && cloud.stamp > motion_.last_stamp()) {
        const Eigen::Isometry3d T_odom_mid = r.T_odom_lidar * scan_.T_stamp_mid;
        registration::Vector6d sweep = motion_.velocity_to(cloud.stamp, T_odom_mid);
        if (prior_ != nullptr) prior_->deskew_velocity(cloud, &sweep);  // measured over the sweep
        preprocessor_.redeskew_map_points(sweep, &scan_);
        r.T_odom_lidar = T_odom_mid * scan_.T_stamp_mid.inverse();
        r.deskewed = scan_.deskewed;
    }
    // How well each rotation would have predicted a scan that measured its own.
    if (sparse && (r.registered() || r.status == FrameStatus::kDegenerate)) {
        heading_.observe(
            registration::rotation_angle(extrapolated.inverse() * r.T_odom_lidar),
            registration::rotation_angle(motion_.last_pose().inverse() * r.T_odom_lidar));
    }
    accept(r);
    lap();
    // A degenerate scan's position along its weak direction is a guess: it stays out of the map
    // (which the next scans are measured against), but for the first scans of a segment: a map of
    // one scan left the next scans of a turn nothing to fit (SlamSegments).
    // (A scan degenerate only where the registration could not observe, the walls of a corridor,
    // goes in: its position there is the prediction's, the best there is.)
    if (!kept_out || segment_scans_ < kYoungSegmentScans) {
        integrate(cloud.stamp, &r);
        ++segment_scans_;
    }
    r.update_ms = lap();
    return r;
}

void Odometry::restart_segment(const std::string& why, const Eigen::Isometry3d& predicted,
                               double since_tracked, FrameResult* r) {
    // Nothing of the old maps is trusted any more. They are ended (handed over intact), and this
    // scan starts a new segment at the best estimate.
    maps_.start_new_segment();
    keyframes_.reset();
    segment_scans_ = 0;
    kept_out_run_ = 0;
    // The new map holds this one scan: the next scans fit it as the first scans of the run fit
    // theirs, not as well as a grown map did. Judged by the grown map's figures, every scan after
    // a kidnap was refused, and the odometry restarted every restart_after.
    typical_rms_ = early_rms_;
    typical_inliers_ = early_inliers_;
    typical_overlap_ = early_overlap_;
    std::ostringstream s;
    s << why << ": new local map in segment " << maps_.segment() << " at the predicted pose";
    r->T_odom_lidar = predicted;
    *r = reject(*r, FrameStatus::kRestarted, s.str());
    r->lost_for = since_tracked;
    r->segment = maps_.segment();
}

bool Odometry::stamp_refused(const common::PointCloud& cloud, FrameResult* r) {
    if (!std::isfinite(cloud.stamp)) {
        *r = reject(*r, FrameStatus::kRejectedStamp, "scan stamp is not finite");
        return true;
    }
    if (has_stamp_ && !(cloud.stamp > last_stamp_)) {
        std::ostringstream s;
        s.precision(17);
        s << "time went backwards: scan stamp " << cloud.stamp << " is not after the previous "
          << last_stamp_;
        *r = reject(*r, FrameStatus::kRejectedStamp, s.str());
        return true;
    }
    return false;
}

void Odometry::integrate(double stamp, FrameResult* r) {
    r->new_local_map = maps_.integrate(scan_.map_points, r->T_odom_lidar, stamp);
    r->local_map_id = maps_.current().id();
    if (keyframes_.check(r->T_odom_lidar)) {
        Keyframe k;
        k.id = next_keyframe_id_++;
        k.stamp = stamp;
        k.T_odom_lidar = r->T_odom_lidar;
        k.local_map_id = r->local_map_id;
        k.points = scan_.map_points;
        r->keyframe = std::move(k);
    }
}

FrameResult Odometry::place_frame(const common::PointCloud& cloud,
                                  const Eigen::Isometry3d& T_odom_lidar) {
    const auto t0 = std::chrono::steady_clock::now();
    FrameResult r;
    r.stamp = cloud.stamp;
    r.input_points = cloud.size();
    r.T_odom_lidar = motion_.poses() ? motion_.last_pose() : initial_pose_;
    if (!maps_.empty()) r.local_map_id = maps_.current().id();
    r.segment = maps_.segment();
    if (stamp_refused(cloud, &r)) return r;
    if (!T_odom_lidar.matrix().allFinite()) {
        return reject(r, FrameStatus::kLost, "given pose is not finite; scan left out");
    }
    // De-skewed by the motion from the last given pose (none for the first scan).
    registration::Vector6d velocity = registration::Vector6d::Zero();
    const bool moving = motion_.poses() > 0 && cloud.stamp > motion_.last_stamp();
    if (moving) {
        velocity = registration::se3_log(motion_.last_pose().inverse() * T_odom_lidar) /
                   (cloud.stamp - motion_.last_stamp());
    }
    preprocessor_.run(cloud, moving ? &velocity : nullptr, &scan_);
    r.dropped_non_finite = scan_.dropped_non_finite;
    r.dropped_range = scan_.dropped_range;
    r.map_points = scan_.map_points.size();
    r.registration_points = scan_.registration_points.size();
    r.deskewed = scan_.deskewed;
    r.T_odom_lidar = T_odom_lidar;
    const auto t1 = std::chrono::steady_clock::now();
    r.preprocess_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
    if (scan_.registration_points.size() < std::size_t(config_.min_scan_points)) {
        std::ostringstream s;
        s << "scan skipped: " << scan_.registration_points.size() << " usable points of "
          << cloud.size() << " (" << scan_.dropped_non_finite << " non-finite), fewer than "
          << config_.min_scan_points;
        r = reject(r, FrameStatus::kSkippedTooFewPoints, s.str());
        has_stamp_ = true;
        last_stamp_ = cloud.stamp;
        motion_.push(cloud.stamp, T_odom_lidar);
        return r;
    }
    r.status = maps_.empty() ? FrameStatus::kInitialised : FrameStatus::kTracked;
    r.covariance.setZero();  // given, not estimated
    lost_ = false;
    accept(r);
    integrate(cloud.stamp, &r);
    r.update_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
    return r;
}

registration::RegistrationResult Odometry::coarse_align(const Eigen::Isometry3d& guess_map,
                                                        registration::Registration& registration) {
    return registration.align(coarse_points_, *maps_.current().coarse(), guess_map);
}

bool Odometry::excellent(const FrameResult& r) const {
    return r.converged && typical_overlap_ > 0.0 && r.overlap >= 0.9 * typical_overlap_ &&
           r.inlier_fraction >= 0.95 * typical_inliers_ && r.residual_rms <= 1.1 * typical_rms_;
}

std::string Odometry::try_register(const Eigen::Isometry3d& guess_odom, double dt, FrameResult* r) {
    const LocalMap& map = maps_.current();
    const Eigen::Isometry3d T_odom_map = map.T_odom_map();
    Eigen::Isometry3d guess = T_odom_map.inverse() * guess_odom;
    if (map.coarse() != nullptr) {
        const registration::RegistrationResult coarse = coarse_align(guess, coarse_registration_);
        r->coarse_iterations += coarse.iterations;
        if (coarse.ok()) guess = coarse.T_map_lidar;
    }
    const registration::RegistrationResult reg =
        registration_.align(scan_.registration_points, map.voxels(), guess);
    r->iterations = reg.iterations;
    r->correspondences = reg.correspondences;
    r->inlier_fraction = reg.inlier_fraction();
    r->overlap = reg.overlap();
    r->inliers = reg.inliers;
    r->residual_rms = reg.residual_rms;
    r->converged = reg.status == registration::RegistrationResult::Status::kConverged;
    const Eigen::Isometry3d estimate = T_odom_map * reg.T_map_lidar;
    const TrackingConfig& c = config_.tracking;
    // The motion since the last tracked scan, against what the platform can do.
    const Eigen::Isometry3d motion = last_tracked_pose_.inverse() * estimate;
    const double moved = motion.translation().norm();
    const double turned = registration::rotation_angle(motion) * kRadToDeg;
    // Back from lost, a fit must be as good as the tracked scans' usually are: a recovery at a
    // wrong place is worse than a restart (which the back end knows to join by a loop).
    const double min_fraction =
        lost_ ? std::max(c.min_inlier_fraction, c.recover_inlier_ratio * typical_inliers_)
              : c.min_inlier_fraction;
    std::ostringstream why;
    why.precision(3);
    if (!reg.ok()) {
        why << "registration failed: " << to_string(reg.status) << " (" << reg.correspondences
            << " correspondences)";
    } else if (!estimate.matrix().allFinite()) {
        why << "registration produced a non-finite pose";
    } else if (reg.inlier_fraction() < min_fraction) {
        why << "only " << 100.0 * reg.inlier_fraction() << " % of " << reg.correspondences
            << " correspondences fit (at least " << 100.0 * min_fraction << " % within "
            << config_.registration.inlier_distance << " m" << (lost_ ? ", when lost" : "") << ")";
    } else if (typical_rms_ > 0.0 && reg.residual_rms > c.max_residual_ratio * typical_rms_) {
        why << "residual " << reg.residual_rms << " m RMS, over " << c.max_residual_ratio
            << " x the recent " << typical_rms_ << " m";
    } else if (moved > c.max_speed * dt + config_.voxel_size ||
               turned > c.max_angular_speed * dt + 5.0) {
        why << "implausible motion: " << moved << " m / " << turned << " deg in " << dt
            << " s (limits " << c.max_speed << " m/s, " << c.max_angular_speed << " deg/s)";
    } else if (const std::string off =
                   prior_ == nullptr ? std::string()
                                     : prior_->disagreement(last_tracked_pose_, last_tracked_stamp_,
                                                            last_tracked_stamp_ + dt, estimate);
               !off.empty()) {
        why << off;
    } else if (!r->converged && (reg.last_step_translation > c.max_final_step_translation ||
                                 reg.last_step_rotation * kRadToDeg > c.max_final_step_rotation)) {
        why << "registration did not converge in " << reg.iterations << " iterations (last step "
            << reg.last_step_translation << " m / " << reg.last_step_rotation * kRadToDeg
            << " deg)";
    }
    if (why.str().empty()) {
        r->T_odom_lidar = estimate;
        r->covariance = honest_covariance(reg.covariance, config_.observability);
        r->information = reg.hessian;
        r->degenerate_directions = reg.degenerate_directions;
        r->min_information = reg.min_information;
    }
    return why.str();
}

bool Odometry::doubtful(const FrameResult& r) const {
    const TrackingConfig& c = config_.tracking;
    return !r.converged ||
           (typical_rms_ > 0.0 && r.residual_rms > c.retry_residual_ratio * typical_rms_) ||
           (typical_inliers_ > 0.0 &&
            r.inlier_fraction < c.retry_inlier_ratio * typical_inliers_) ||
           (typical_overlap_ > 0.0 && r.overlap < c.retry_overlap_ratio * typical_overlap_);
}

std::string Odometry::search(const Eigen::Isometry3d& predicted, double dt, FrameResult* best) {
    const TrackingConfig& c = config_.tracking;
    // The guesses: the last pose (a wrong velocity), then the prediction turned about the
    // sensor's z axis, nearest turns first.
    std::vector<Eigen::Isometry3d> guesses;
    const Eigen::Isometry3d& last = motion_.last_pose();
    const Eigen::Isometry3d jump = last.inverse() * predicted;
    if (jump.translation().norm() > 0.01 || registration::rotation_angle(jump) > 0.1 / kRadToDeg) {
        guesses.push_back(last);
    }
    const int steps = c.yaw_search > 0.0 ? int(std::floor(c.yaw_search / c.yaw_step + 1e-9)) : 0;
    for (int k = 1; k <= steps; ++k) {
        for (const int sign : {1, -1}) {
            const double yaw = sign * k * c.yaw_step / kRadToDeg;
            guesses.push_back(predicted * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
        }
    }
    if (guesses.empty()) return "nothing to search (tracking.yaw_search is 0)";
    const LocalMap& map = maps_.current();
    const Eigen::Isometry3d T_map_odom = map.T_odom_map().inverse();
    // With a coarse grid, every guess is probed on it (a few iterations) and only the two that
    // fit best are registered (coarse, then fine); without one, every guess is registered.
    struct Start {
        Eigen::Isometry3d guess_odom;
        std::size_t score;
        Eigen::Isometry3d probed;  // the guess it came from
    };
    std::vector<Start> starts;
    int coarse_iterations = 0;
    const auto probe = [&](const Eigen::Isometry3d& g) {
        if (map.coarse() == nullptr) {
            starts.push_back({g, 0, g});
            return;
        }
        const registration::RegistrationResult coarse =
            coarse_align(T_map_odom * g, probe_registration_);
        coarse_iterations += coarse.iterations;
        if (!coarse.ok()) return;
        starts.push_back({map.T_odom_map() * coarse.T_map_lidar, coarse.inliers, g});
    };
    for (const Eigen::Isometry3d& g : guesses) probe(g);
    const auto by_score = [](const Start& a, const Start& b) { return a.score > b.score; };
    std::stable_sort(starts.begin(), starts.end(), by_score);
    // Coarse to fine in yaw: a probe barely turns (its basin in yaw is a few degrees where the
    // translation is also off, as at a corner 1 s after the last scan), so the best guess is
    // probed again turned by +-yaw_refine; the best of all go on.
    // Only with a velocity (a turn extrapolated past a corner) and not back from lost (a recovery
    // must fit as the recent scans do; SlamSegments: a +-5 deg probe after two empty seconds in a
    // turn recovered 8 m / 180 deg off): a first step's guesses all stay
    // short of a long step, and a finer turn only picks among equally wrong fits.
    if (map.coarse() != nullptr && c.yaw_refine > 0.0 && motion_.poses() >= 2 && !lost_ &&
        !starts.empty()) {
        const Eigen::Isometry3d centre = starts.front().probed;
        for (const int sign : {1, -1}) {
            const double yaw = sign * c.yaw_refine / kRadToDeg;
            probe(centre * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
        }
        std::stable_sort(starts.begin(), starts.end(), by_score);
    }
    if (map.coarse() != nullptr && starts.size() > 2) starts.resize(2);
    std::string first_why = "no guess reached the map's coarse grid";
    bool found = false;
    const FrameResult blank = *best;
    for (const Start& s : starts) {
        FrameResult attempt = blank;
        const std::string why = try_register(s.guess_odom, dt, &attempt);
        ++best->attempts;
        if (!why.empty()) {
            if (!found && &s == &starts.front()) first_why = why;
            continue;
        }
        if (!found || attempt.inliers > best->inliers) {
            const int tries = best->attempts;
            *best = attempt;
            best->attempts = tries;
            found = true;
        }
    }
    best->coarse_iterations = coarse_iterations;
    std::ostringstream s;
    s << guesses.size() << " guesses, the best: " << first_why;
    return found ? std::string() : s.str();
}

void Odometry::learn(const FrameResult& r) {
    if (r.registered() && r.constrained_directions == 3 && motion_.poses() > 0 &&
        r.stamp > motion_.last_stamp()) {
        observed_speed_ =
            (r.T_odom_lidar.translation() - motion_.last_pose().translation()).norm() /
            (r.stamp - motion_.last_stamp());
    }
    if (early_frames_ < kEarlyFrames) {
        const double n = double(++early_frames_);
        early_rms_ += (r.residual_rms - early_rms_) / n;
        early_inliers_ += (r.inlier_fraction - early_inliers_) / n;
        early_overlap_ += (r.overlap - early_overlap_) / n;
    }
    typical_rms_ = typical_rms_ > 0.0 ? 0.9 * typical_rms_ + 0.1 * r.residual_rms : r.residual_rms;
    typical_inliers_ = typical_inliers_ > 0.0 ? 0.9 * typical_inliers_ + 0.1 * r.inlier_fraction
                                              : r.inlier_fraction;
    typical_overlap_ =
        typical_overlap_ > 0.0 ? 0.9 * typical_overlap_ + 0.1 * r.overlap : r.overlap;
}

void Odometry::accept(const FrameResult& result) {
    if (prior_ != nullptr) {
        prior_->observe(result.stamp, result.T_odom_lidar.linear(), result.registered());
    }
    has_stamp_ = true;
    last_stamp_ = result.stamp;
    last_tracked_stamp_ = result.stamp;
    last_tracked_pose_ = result.T_odom_lidar;
    if (motion_.poses() > 0) {
        // A step that did not measure its turn counts as none: the recent rate fades.
        const double dt = result.stamp - motion_.last_stamp();
        recent_turn_.add(
            result.turn_measured ? turn_rate(motion_.last_pose(), result.T_odom_lidar, dt) : 0.0,
            dt, config_.tracking.spin_window);
    }
    motion_.push(result.stamp, result.T_odom_lidar, scan_.T_stamp_mid);
    if (result.degenerate()) {
        motion_.damp(result.degenerate_directions, config_.registration.degeneracy_length,
                     config_.tracking.degenerate_velocity_keep,
                     config_.tracking.degenerate_travel_keep,
                     config_.tracking.degenerate_travel_turn * M_PI / 180.0);
    }
}

void Odometry::finish_local_maps() { maps_.finish_all(); }

}  // namespace ltm::odometry
