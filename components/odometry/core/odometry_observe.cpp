// Odometry: the observability check of an accepted fit (issue 27; observability.hpp for the
// criterion, step_search.hpp for the search along a weak direction).
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "odometry/core/odometry.hpp"
#include "odometry/core/step_search.hpp"

namespace ltm::odometry {

bool Odometry::check_observability(const Eigen::Isometry3d& predicted, double dt, FrameResult* r) {
    const ObservabilityConfig& c = config_.observability;
    const LocalMap& map = maps_.current();
    const Eigen::Isometry3d T_odom_map = map.T_odom_map();
    const Observability o = translation_observability(r->information, c.weak_information);
    r->translation_information = o.information;
    r->constrained_directions = o.constrained;
    r->weak_direction = T_odom_map.linear() * o.weakest();
    // No velocity yet after a gap (tracking.search_after; at 10 Hz a first step stays within the
    // basin), or the last scan was degenerate: the prediction is a guess.
    // A restart's first step is a run's first step: the new segment's map holds one scan, and the
    // velocity is the one carried through the loss (the restart scan's pose is a prediction).
    const bool fresh = motion_.poses() < 2 || segment_scans_ < 2;
    const bool guessed = unobserved_ || (fresh && dt > config_.tracking.search_after);
    unobserved_ = false;
    // The first step of a run predicts no motion: a fit of a scan taken several metres on can
    // stay where it started even in a well constrained street (its basin is a few voxels), and
    // every later prediction inherits that. It is searched along the sensor's forward axis too.
    // (Doing the same after a degenerate scan, whose velocity is also a guess, made the
    // kitti00_path every-10th case worse: 41 m ATE instead of 32 m, wrong peaks at corners.)
    // Only after a gap (tracking.search_after): at 10 Hz a first step stays within the basin.
    // The same after a restart (tree_road VLP-16 every 10th scan: scan 2 of a new segment slid
    // more than 1 m fitting its one-scan map from the carried velocity).
    const bool first_step = fresh && dt > config_.tracking.search_after;
    const Eigen::Vector3d last = motion_.last_pose().translation();
    const Eigen::Vector3d step =
        first_step ? Eigen::Vector3d::Zero() : Eigen::Vector3d(predicted.translation() - last);
    if (!o.weak() && !first_step) return true;
    // The direction searched: the weakest; when two are weak, the predicted motion (without a
    // velocity yet: the sensor's forward axis) within the weak plane, where a vehicle moves.
    Eigen::Vector3d v = o.weak()            ? r->weak_direction
                        : step.norm() > 0.5 ? Eigen::Vector3d(step.normalized())
                                            : Eigen::Vector3d(r->T_odom_lidar.linear().col(0));
    if (o.constrained <= 1) {
        const Eigen::Vector3d u = step.norm() > 0.5
                                      ? Eigen::Vector3d(step.normalized())
                                      : Eigen::Vector3d(r->T_odom_lidar.linear().col(0));
        const Eigen::Vector3d v2 = T_odom_map.linear() * o.directions.col(1);
        const Eigen::Vector3d in_plane = v * v.dot(u) + v2 * v2.dot(u);
        if (in_plane.norm() > 0.3) v = in_plane.normalized();
    }
    // The steps since the last pose along it: the fit's and the prediction's.
    // The search starts from the fit; on a first step in a constrained scene from the
    // prediction (the fit's rotation may have turned to make up for the missing step).
    const Eigen::Isometry3d start = o.weak() ? r->T_odom_lidar : predicted;
    const double s_fit = v.dot(start.translation() - last);
    const double s_pred = v.dot(predicted.translation() - last);
    const double d = s_pred - s_fit;
    // A small step that the fit agrees with is within the fit's basin: trusted (a direction
    // nothing constrains is then at the prediction by the registration's solution remapping and
    // reported in degenerate_directions). Checked: a fit short of or beyond the prediction, a
    // long step, the first step, an unconstrained direction after a gap.
    const bool disagrees = std::abs(d) > c.slide_tolerance + c.slide_fraction * std::abs(s_pred);
    // Between scans further apart than tracking.search_after a direction nothing constrains
    // (below registration.degeneracy_ratio) is always checked: the prediction over a long gap
    // is a guess, and a fit agreeing with it proves nothing.
    const bool unconstrained = o.information[0] < config_.registration.degeneracy_ratio &&
                               dt > config_.tracking.search_after;
    if (!disagrees && std::abs(s_pred) < c.search_step && !guessed && !unconstrained) return true;

    // Where along v does the scan fit? From the fit, over the fit and the prediction and a
    // margin either side.
    // Without a velocity yet (the first step of a run: no motion predicted) or after a degenerate
    // scan (the velocity along the weak direction is a guess), the search covers
    // first_step_range either side.
    const double margin = guessed ? std::max(c.min_margin, c.first_step_range)
                                  : std::max(c.min_margin, c.margin_fraction * std::abs(s_pred));
    ProfileRequest q;
    q.from = std::min(0.0, d) - margin;
    q.to = std::max(0.0, d) + margin;
    q.spacing = config_.voxel_size;
    q.peak_width = c.peak_width;
    q.kernel = config_.registration.inlier_distance;
    const Eigen::Isometry3d T_map_fit = T_odom_map.inverse() * start;
    const Eigen::Vector3d v_map = T_odom_map.linear().transpose() * v;
    const Profile p = search_along(coarse_points_, map.voxels(), registration_.imls_params(),
                                   T_map_fit, v_map, q);
    r->profile_contrast = p.contrast();
    r->profile_support = p.best_support;
    ++r->attempts;
    // A first step in a constrained scene only asks for a peak above first_step_contrast: the fit
    // from it is judged again by the registration's own checks.
    const double contrast = o.weak() ? c.min_contrast : c.first_step_contrast;
    const bool observable = p.best_support >= c.min_support && p.contrast() >= contrast;
    // The first step of a run: the fit's own position stands. After a restart the restart scan's
    // pose is itself a guess and its one-scan map may be a few trunks (tree_road VLP-16 every 10th
    // scan: scan 2 fitted 4.6 m short, constrained every way, the search flat at contrast 1.06):
    // without a distinct peak the step is not observed, and the scan is flagged.
    const bool after_restart = first_step && motion_.poses() >= 2;
    if (!observable && !o.weak() && !after_restart) return true;
    // Degenerate: the position along v is not fixed by this scan. It becomes the motion model's
    // only when that is a motion model (a velocity, or wheel odometry) and the scan does not
    // place the fit distinctly better than the prediction (directional support at the fit at most
    // min_contrast times the prediction's): a replacement may not be worse on the residual the
    // search measures. Otherwise the fit's own position stands, flagged (the first step of a run
    // at 5 Hz: the fit had moved 0.8 m, the prediction none; SlamSegments).
    const auto degenerate = [&](const char* fit_used) {
        r->weak_direction = v;
        r->search_used = fit_used;
        unobserved_ = true;
        // (Not after a restart: its velocity is the one carried through the loss.)
        const bool informed =
            (motion_.poses() >= 2 && !first_step) || (prior_ != nullptr && prior_->has_wheel());
        if (informed) {
            const Eigen::Isometry3d T_map_pred = Eigen::Translation3d(d * v_map) * T_map_fit;
            const registration::ImlsParams& imls = registration_.imls_params();
            const double at_fit =
                directional_support(coarse_points_, map.voxels(), imls, T_map_fit, v_map, q.kernel)
                    .support;
            const double at_pred =
                directional_support(coarse_points_, map.voxels(), imls, T_map_pred, v_map, q.kernel)
                    .support;
            if (at_fit <= c.min_contrast * std::max(at_pred, 1.0)) {
                r->T_odom_lidar.translation() += d * v;
                r->search_used = "motion model";
            }
        }
        return false;  // inflate_covariance widens the covariance along the weak directions
    };
    // No distinct peak, or one whose fit is no better: does the fit itself have a basin along v?
    // Then its position there is observed (the support profile is a coarse proxy: among a
    // narrow view's few surfaces that see v it is flat while the fit converges).
    const auto basin = [&] {
        if (c.basin_offset <= 0.0 || first_step) return false;
        double offset = std::max(std::abs(d), c.basin_offset);
        if (guessed) {
            // After a degenerate scan the prediction along v is a guess: the basin has to cover
            // half the expected step, which needs a speed measured in a scan constrained every
            // way (a road whose every scan is weak never measured one: its fits can sit in a
            // basin a whole step short).
            if (observed_speed_ <= 0.0) return false;
            const double expected = std::max(std::abs(s_pred), observed_speed_ * dt);
            offset = std::max(offset, c.weak_sigma_fraction * expected);
        }
        if (offset > c.basin_max_offset || !fit_has_basin(*r, v, offset, dt)) return false;
        r->attempts += 2;
        r->weak_direction = v;
        r->search_used = "fit (converges)";
        return true;
    };
    if (!observable) return basin() || degenerate("fit (weak)");
    if (std::abs(p.best_offset) <= 0.5 * q.spacing && o.weak()) {
        r->search_used = "along (fit confirmed)";
        return true;
    }
    // The fit slid: registered again from the best position along v.
    Eigen::Isometry3d guess = start;
    guess.translation() += p.best_offset * v;
    FrameResult again = *r;
    const std::string why = try_register(guess, dt, &again);
    ++r->attempts;
    const double stayed = std::abs(v.dot(again.T_odom_lidar.translation() - guess.translation()));
    const bool held = why.empty() && stayed <= c.peak_width;
    // A replacement must beat the fit it replaces on the registration's own residual: more of
    // the same scan points within registration.inlier_distance of the same map. When it does
    // not, the fit stands: in a scene constrained every way (a first step) as it is; along a weak
    // direction flagged, since the search and the fit disagree on where the scan is.
    if (!(held && again.inliers > r->inliers)) {
        if (!o.weak()) {
            r->search_used = "along (fit kept)";
            return true;
        }
        return basin() || degenerate("along (fit kept, weak)");
    }
    const int attempts = r->attempts;
    *r = again;
    r->attempts = attempts;
    r->profile_shift = p.best_offset;
    r->weak_direction = v;
    r->search_used = "along";
    return true;
}

bool Odometry::fit_has_basin(const FrameResult& r, const Eigen::Vector3d& v, double offset,
                             double dt) {
    const double tolerance = config_.observability.basin_tolerance;
    for (const double side : {-offset, offset}) {
        Eigen::Isometry3d guess = r.T_odom_lidar;
        guess.translation() += side * v;
        FrameResult again = r;
        if (!try_register(guess, dt, &again).empty()) return false;
        const double off =
            std::abs(v.dot(again.T_odom_lidar.translation() - r.T_odom_lidar.translation()));
        if (off > tolerance) return false;
    }
    return true;
}

void Odometry::inflate_covariance(const Eigen::Isometry3d& predicted, double dt,
                                  FrameResult* r) const {
    const ObservabilityConfig& c = config_.observability;
    const Observability o = translation_observability(r->information, c.weak_information);
    if (!o.weak()) return;
    const double expected = std::max(
        (predicted.translation() - motion_.last_pose().translation()).norm(), observed_speed_ * dt);
    const bool degenerate = r->status == FrameStatus::kDegenerate;
    const double sigma =
        degenerate ? std::max(c.degenerate_min_sigma, c.degenerate_sigma_fraction * expected)
                   : std::max(c.weak_min_sigma, c.weak_sigma_fraction * expected);
    // A position the search along the weak direction found (a distinct peak) is measured.
    const std::string used = r->search_used;
    const bool found = !degenerate && (used == "along" || used == "along (fit confirmed)" ||
                                       used == "fit (converges)");
    inflate_weak(o, maps_.current().T_odom_map().linear(),
                 found ? r->weak_direction : Eigen::Vector3d::Zero(), sigma, &r->covariance);
}

bool Odometry::spinning(double rate) const {
    const double threshold = config_.tracking.spin_rate;
    // Not with wheel odometry: it measures the translation.
    return threshold > 0.0 && rate >= threshold && !(prior_ != nullptr && prior_->has_wheel());
}

void Odometry::hold_while_spinning(bool kept_out, FrameResult* r) const {
    if (!spinning(r->turn_rate)) return;
    std::vector<Eigen::Vector3d> unobserved = translation_parts(r->degenerate_directions);
    if (kept_out) {
        const Observability o =
            translation_observability(r->information, config_.observability.weak_information);
        const Eigen::Matrix3d R_odom_map = maps_.current().T_odom_map().linear();
        for (int k = 0; k < 3 - o.constrained; ++k)
            unobserved.push_back(R_odom_map * o.directions.col(k));
        unobserved.push_back(r->weak_direction);
    }
    if (unobserved.empty()) return;
    r->spin_held = hold_along(motion_.last_pose().translation(), unobserved, &r->T_odom_lidar);
    r->spin_hold = true;
    std::ostringstream s;
    s.precision(3);
    s << "; turning " << r->turn_rate << " deg/s (at least tracking.spin_rate "
      << config_.tracking.spin_rate << "): held at the last position there (moved " << r->spin_held
      << " m)";
    r->message += s.str();
}

}  // namespace ltm::odometry
