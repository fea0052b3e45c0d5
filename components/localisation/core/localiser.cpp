#include "localisation/core/localiser.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "registration/core/imls.hpp"
#include "registration/core/loop_verifier.hpp"
#include "registration/core/se3.hpp"

namespace ltm::localisation {

namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

const char* to_string(LocalisationState state) {
    switch (state) {
        case LocalisationState::kInitialising:
            return "initialising";
        case LocalisationState::kTracking:
            return "tracking";
        case LocalisationState::kLost:
            return "lost";
        case LocalisationState::kRelocalised:
            return "relocalised";
        case LocalisationState::kOffMap:
            return "off_map";
    }
    return "unknown";
}

std::optional<common::ConfigProblem> validate(const LocaliserConfig& config) {
    LocaliserConfig c = config;
    common::ConfigChecker k;
    visit_fields(c, k);
    k.include(validate(config.global), "global.");
    k.include(registration::validate(config.tracking), "tracking.");
    if (const auto problem = k.problem()) return problem;
    try {
        validate(config.neighbourhood);
    } catch (const common::ConfigError& e) {
        return common::ConfigProblem{e.key(), e.problem()};
    }
    return std::nullopt;
}

LocaliserConfig localiser_preset(common::SensorPreset preset) {
    const common::SensorPresetRow& row = common::sensor_preset_row(preset);
    LocaliserConfig c;
    // The verification of a place as the mapper's loops for this sensor (the rest of it stricter:
    // GlobalLocaliserConfig::verification_defaults).
    c.global.verification.downsample = row.places.verify_downsample;
    c.global.verification.min_inliers = row.places.verify_min_inliers;
    c.global.verification.coarse_factor = row.places.verify_coarse_factor;
    // A narrow view's probe can end in a poorer minimum beside the right pose that the fine pass
    // alone accepts (GlobalLocaliserConfig::fine_only): both passes there.
    c.global.fine_only = row.horizontal_fov_deg >= 360.0;
    // ... and its keyframes a few metres apart or turned see different things: the ring keys'
    // neighbours are compared with the full descriptor as they come, none skipped as a clump
    // of one place (GlobalLocaliserConfig::candidate_separation), 25 of them as before the
    // separation came.
    // ... and a handheld one is pitched from the map's keyframes of a place (hku-avia: by up to
    // 17 deg): its descriptor is also made turned by +-15 deg (GlobalLocaliserConfig::
    // tilt_offsets; session 2 on session 1, 260 -> 265 of 266 right, 0 wrong).
    if (row.horizontal_fov_deg < 360.0) {
        c.global.candidate_separation = 0.0;
        c.global.candidates = 25;
        c.global.tilt_offsets = {0.0, 15.0, -15.0};
    }
    c.off_map_margin = row.localisation.off_map_margin;
    return c;
}

LocalisationMapConfig localisation_map_preset(common::SensorPreset preset) {
    const common::SensorPresetRow& row = common::sensor_preset_row(preset);
    LocalisationMapConfig c;
    c.coarse_factor = row.places.verify_coarse_factor;
    c.features.max_range = row.localisation.feature_max_range;
    return c;
}

namespace {

const LocaliserConfig& checked(const LocaliserConfig& config) {
    if (auto problem = validate(config)) throw common::ConfigError("localisation", *problem);
    return config;
}

}  // namespace

Localiser::Localiser(std::shared_ptr<const LocalisationMap> map, const LocaliserConfig& config)
    : map_(std::move(map)),
      config_(checked(config)),
      global_(map_, config.global),
      tracker_(config.tracking, map_->voxel_size()) {}

void Localiser::set_initial_pose(const PoseHint& hint) {
    hint_ = hint;
    last_global_ = -1e300;
    handover_.hint_changed();  // a query out was asked without it
}

void Localiser::thin(const std::vector<Eigen::Vector3f>& points) {
    sampler_.sample(points, config_.downsample, std::size_t(config_.max_points), &sampled_);
}

bool Localiser::run_global(double stamp, const std::vector<Eigen::Vector3f>& points,
                           const Eigen::Isometry3d& T_odom_lidar, LocalisationUpdate* u) {
    last_global_ = stamp;
    const GlobalLocalisation g = global_.localise(points, hint_);
    u->global_ran = true;
    u->global_time_s = g.time_s;
    if (!g.localised) {
        u->message = g.reason;
        return false;
    }
    hint_.reset();
    // Paged: tracking goes on at once on the local maps the answer was verified on.
    if (neighbourhood_) neighbourhood_->adopt(g.around, g.T_map_lidar.translation());
    T_map_odom_ = g.T_map_lidar * T_odom_lidar.inverse();
    T_map_lidar_ = g.T_map_lidar;
    u->T_map_lidar = g.T_map_lidar;
    u->covariance = g.covariance;
    u->confidence = g.confidence;
    u->inlier_fraction = g.inlier_fraction;
    u->message = "relocalised: " + g.reason;
    have_fix_ = true;
    last_fix_ = last_good_ = stamp;
    return true;
}

const registration::VoxelGrid& Localiser::tracking_grid() const {
    return neighbourhood_ ? neighbourhood_->current()->target->fine : map_->target().fine;
}

registration::SectorOverlap Localiser::weakest_sector(const Eigen::Isometry3d& T_map_lidar) const {
    if (!(config_.edge_sector_overlap > 0.0)) return {};
    return registration::sector_overlap(sampled_, tracking_grid(), T_map_lidar,
                                        tracker_.imls_params(), config_.inlier_distance,
                                        config_.edge_sectors, 0.1);
}

bool Localiser::track(const Eigen::Isometry3d& predicted, LocalisationUpdate* u) {
    const registration::RegistrationResult r = tracker_.align(sampled_, tracking_grid(), predicted);
    std::ostringstream why;
    why.precision(3);
    if (!r.ok() || !r.T_map_lidar.matrix().allFinite()) {
        why << "registration " << registration::to_string(r.status);
    } else {
        const Eigen::Isometry3d d = predicted.inverse() * r.T_map_lidar;
        const double dt = d.translation().norm();
        const double dr = registration::rotation_angle(d) / kDegToRad;
        u->inlier_fraction = r.inlier_fraction();
        if (r.inlier_fraction() < config_.min_inlier_fraction) {
            why << "inlier fraction " << r.inlier_fraction() << " below "
                << config_.min_inlier_fraction;
        } else if (r.overlap() < config_.min_overlap) {
            why << "overlap with the map " << r.overlap() << " below " << config_.min_overlap;
        } else if (dt > config_.max_correction_translation ||
                   dr > config_.max_correction_rotation) {
            // The map fits far from where the odometry says: the odometry jumped (a young map
            // after a restart, a bad registration) or the robot was moved. A fit that passes
            // global localisation's verification there is kept; otherwise it is not tracking.
            const GlobalLocalisation v = global_.verify(sampled_, r.T_map_lidar);
            if (v.localised) {
                T_map_lidar_ = v.T_map_lidar;
                u->T_map_lidar = v.T_map_lidar;
                u->covariance = v.covariance;
                u->confidence = v.confidence;
                u->inlier_fraction = v.inlier_fraction;
                std::ostringstream s;
                s.precision(3);
                s << "the odometry is " << dt << " m / " << dr
                  << " deg off the map here; the map's fit (verified) is kept";
                u->message = s.str();
                return true;
            }
            why << "the map fits " << dt << " m / " << dr << " deg away from the odometry's pose ("
                << v.reason << ")";
        } else {
            const Eigen::Matrix3f R = r.T_map_lidar.linear().cast<float>();
            const Eigen::Vector3f t = r.T_map_lidar.translation().cast<float>();
            registration::ImlsResult res;
            std::size_t structure = 0, on = 0;
            // With the neighbours the registration found (most points stayed in their voxel).
            for (std::size_t i = 0; i < sampled_.size(); ++i) {
                if (!tracker_.imls_after_align(i, tracking_grid(), R * sampled_[i] + t, &res) ||
                    std::abs(res.normal.z()) >= 0.8f)
                    continue;
                ++structure;
                on += std::abs(res.distance) <= config_.inlier_distance;
            }
            const double ratio = structure ? double(on) / double(structure) : 1.0;
            if (structure >= std::size_t(config_.min_structure_points) &&
                ratio < config_.min_structure_inlier_ratio) {
                why << "structure inlier ratio " << ratio << " below "
                    << config_.min_structure_inlier_ratio;
            }
        }
    }
    if (!why.str().empty()) {
        u->message = "tracking failed: " + why.str();
        return false;
    }
    u->overlap = r.overlap();
    T_map_lidar_ = r.T_map_lidar;
    u->T_map_lidar = r.T_map_lidar;
    u->covariance = r.covariance;
    u->confidence = std::clamp(r.inlier_fraction(), 0.0, 1.0) *
                    std::clamp(r.overlap() / std::max(config_.min_overlap, 1e-6), 0.0, 1.0);
    return true;
}

void Localiser::take_track(const Localiser& from) {
    state_ = from.state_;
    have_fix_ = from.have_fix_;
    T_map_odom_ = from.T_map_odom_;
    T_map_lidar_ = from.T_map_lidar_;
    T_odom_lidar_ = from.T_odom_lidar_;
    segment_ = from.segment_;
    have_odometry_ = from.have_odometry_;
    last_stamp_ = from.last_stamp_;
    last_good_ = from.last_good_;
    last_fix_ = from.last_fix_;
    last_global_ = from.last_global_;
    first_ = from.first_;
    // A global query out for the old localiser answers for this one (the same map frame).
    elsewhere_ = from.elsewhere_;
    recheck_ = from.recheck_;
    handover_ = from.handover_;
    request_ = from.request_;
    answer_ = from.answer_;
}

LocalisationUpdate Localiser::process(double stamp, const std::vector<Eigen::Vector3f>& points,
                                      const std::optional<OdometryInput>& odometry) {
    LocalisationUpdate u;
    u.stamp = stamp;
    // The odometry's pose of this scan; without odometry, the last estimate (a static robot).
    const Eigen::Isometry3d T_odom_lidar =
        odometry ? odometry->T_odom_lidar : T_map_odom_.inverse() * T_map_lidar_;
    std::string suspicion;
    const bool restarted = odometry && have_odometry_ && odometry->segment != segment_;
    if (restarted) {
        suspicion = "the odometry restarted (segment " + std::to_string(odometry->segment) + ")";
    } else if (!first_ && stamp - last_stamp_ > config_.max_gap) {
        std::ostringstream s;
        s << "a gap of " << stamp - last_stamp_ << " s between scans";
        suspicion = s.str();
    }
    if (odometry) {
        have_odometry_ = true;
        segment_ = odometry->segment;
    }
    first_ = false;
    last_stamp_ = stamp;
    thin(points);
    // Elsewhere: the answer of the query out, carried forward to this scan.
    if (answer_ && apply_answer(stamp, T_odom_lidar, &u)) {
        if (!suspicion.empty()) u.message += " (after " + suspicion + ")";
        finish(stamp, &u);
        return u;
    }
    // Elsewhere, the new odometry frame until an answer comes: where the last estimate was (the
    // odometry restarts at the robot's pose); tracking below checks it against the map.
    if (elsewhere_ && restarted && have_fix_) T_map_odom_ = T_map_lidar_ * T_odom_lidar.inverse();

    const bool searching = state_ == LocalisationState::kInitialising ||
                           state_ == LocalisationState::kLost || !have_fix_;
    if (searching || !suspicion.empty() || hint_ || recheck_) {
        const bool due = !searching || hint_ || stamp - last_global_ >= config_.global_every;
        if (elsewhere_) {
            // The query runs elsewhere; meanwhile the search goes on (no pose), or tracking does.
            if (due) ask_global(stamp, points, T_odom_lidar, &u);
            const std::string said = (suspicion.empty() ? "" : suspicion + "; ") + u.message;
            if (searching) {
                if (!due) u.message = "waiting to retry global localisation";
            } else if (track(T_map_odom_ * T_odom_lidar, &u)) {
                state_ = LocalisationState::kTracking;
                last_good_ = stamp;
                u.message = said + "; tracking meanwhile";
            } else {
                T_map_lidar_ = T_map_odom_ * T_odom_lidar;
                state_ = LocalisationState::kLost;
                u.message = said + "; " + u.message;
            }
        } else if (due && run_global(stamp, points, T_odom_lidar, &u)) {
            state_ = LocalisationState::kRelocalised;
            if (!suspicion.empty()) u.message += " (after " + suspicion + ")";
        } else if (searching) {
            if (!due) u.message = "waiting to retry global localisation";
        } else {
            // A suspected kidnap the global query could not settle: keep tracking if the map
            // still agrees with the odometry, else lost.
            const std::string global_reason = u.message;
            if (track(T_map_odom_ * T_odom_lidar, &u)) {
                state_ = LocalisationState::kTracking;
                last_good_ = stamp;
                u.message = suspicion + "; the map still agrees with the odometry";
            } else {
                state_ = LocalisationState::kLost;
                u.message = suspicion + "; " + global_reason;
            }
        }
    } else {
        const Eigen::Isometry3d predicted = T_map_odom_ * T_odom_lidar;
        if (!map_->covers(predicted.translation(), config_.off_map_margin)) {
            state_ = LocalisationState::kOffMap;
            T_map_lidar_ = predicted;
            u.T_map_lidar = predicted;
            u.message = "beyond the map: following the odometry";
            last_good_ = stamp;
        } else if (neighbourhood_ && !neighbourhood_->holds(predicted.translation())) {
            // A fix far from the neighbourhood in use (a relocalisation elsewhere): its build
            // was asked for; until it is in, the pose follows the odometry (not lost).
            state_ = LocalisationState::kOffMap;
            T_map_lidar_ = predicted;
            u.T_map_lidar = predicted;
            u.message = "the map around the pose is loading: following the odometry";
            last_good_ = stamp;
        } else if (track(predicted, &u)) {
            const registration::SectorOverlap sector = weakest_sector(u.T_map_lidar);
            if (u.overlap < config_.edge_overlap ||
                sector.min_fraction < config_.edge_sector_overlap) {
                // The map's edge: the odometry from the last scan the map covered better.
                state_ = LocalisationState::kOffMap;
                T_map_lidar_ = predicted;
                u.T_map_lidar = predicted;
                std::ostringstream s;
                s.precision(2);
                if (u.overlap < config_.edge_overlap) {
                    s << "at the map's edge (overlap " << u.overlap << " below "
                      << config_.edge_overlap << "): following the odometry";
                } else {
                    s << "at the map's edge (" << sector.min_fraction << " explained towards "
                      << int(std::lround(sector.weakest_deg)) << " deg, below "
                      << config_.edge_sector_overlap << "): following the odometry";
                }
                u.message = s.str();
            } else {
                T_map_odom_ = u.T_map_lidar * T_odom_lidar.inverse();
                state_ = LocalisationState::kTracking;
            }
            last_good_ = stamp;
        } else {
            T_map_lidar_ = predicted;
            u.T_map_lidar = predicted;
            if (stamp - last_good_ >= config_.lost_after) {
                state_ = LocalisationState::kLost;
                u.message += " (for " + std::to_string(stamp - last_good_) + " s: lost)";
            }
        }
    }
    finish(stamp, &u);
    return u;
}

void Localiser::finish(double stamp, LocalisationUpdate* u) {
    u->state = state_;
    u->pose_valid = have_fix_ && state_ != LocalisationState::kLost &&
                    state_ != LocalisationState::kInitialising;
    if (!u->pose_valid) u->T_map_lidar = T_map_lidar_;
    u->T_map_odom = T_map_odom_;
    u->lost_for = stamp - last_good_;
    u->since_fix = have_fix_ ? stamp - last_fix_ : 0.0;
    if (u->state == LocalisationState::kOffMap) u->confidence = 0.0;
    if (neighbourhood_ && u->pose_valid) neighbourhood_->update(u->T_map_lidar.translation());
}

}  // namespace ltm::localisation
