#pragma once
// Configuration of the LiDAR odometry (METHOD.md sections 1-2): one plain struct with defaults for
// a Velodyne HDL-64E, plus named presets for other sensors. No I/O in here: the adapter loads YAML.
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "common/core/sensor_preset.hpp"
#include "odometry/core/observability.hpp"
#include "registration/core/registration_config.hpp"

namespace ltm::odometry {

using registration::PreprocessConfig;
using registration::RegistrationConfig;
using registration::VoxelConfig;

// Tracking: when a registration is accepted (the quality of its fit, not the size of the
// correction), how the odometry searches when the prediction fails (fast turns, irregular scan
// spacing), and how it recovers when nothing fits.
struct TrackingConfig {
    // A result is accepted when at least min_inlier_fraction of its correspondences are inliers
    // (residual under registration.inlier_distance), its residual RMS is at most
    // max_residual_ratio times the recent frames', and the motion since the last tracked scan is
    // physically possible. (How much of the scan has a correspondence is not a criterion: a
    // narrow view turning into unmapped space, or a young sparse map, explains little of a scan
    // and still fixes the pose.)
    double min_inlier_fraction = 0.5;
    double max_residual_ratio = 3.0;
    double max_speed = 40.0;                   // [m/s]
    double max_angular_speed = 360.0;          // [deg/s]
    double max_final_step_translation = 0.05;  // unconverged and last step larger: refused [m]
    double max_final_step_rotation = 0.5;      // [deg]
    // A result that is refused, not converged, has a residual RMS above retry_residual_ratio
    // times the recent frames', an inlier fraction below retry_inlier_ratio times theirs or an
    // overlap (correspondences over points) below retry_overlap_ratio times theirs, is retried
    // from the last pose and from the prediction turned by multiples of yaw_step up to
    // +-yaw_search (about the sensor's z axis); the result with the most inliers is kept.
    double retry_residual_ratio = 1.5;
    double retry_inlier_ratio = 0.7;
    double retry_overlap_ratio = 0.7;
    // Scans further apart than this (sensor time since the last tracked one) are always searched:
    // a constant-velocity prediction over a long gap is a guess (keyframe streams, dropouts).
    double search_after = 0.3;  // [s]
    // Back from lost (after refused or skipped scans), a fit needs at least this times the
    // recent inlier fraction: recovering at a wrong place is worse than restarting.
    double recover_inlier_ratio = 0.9;
    // Of the last motion along a direction the registration could not observe (degenerate), the
    // fraction the constant-velocity prediction keeps [0..1]: 1 extrapolates it unchanged (a
    // tunnel), lower values let a wrong velocity there die out (an open field seen by a narrow
    // view, where the prediction alone would carry a sideways drift for ever).
    double degenerate_velocity_keep = 0.5;
    // The same along the way the sensor travels (a degenerate direction within ~26 deg of the last
    // step): 1 goes on at the last speed (down a corridor, where the position along the axis is
    // then the constant-velocity prediction's and every such scan is reported degenerate).
    double degenerate_travel_keep = 1.0;
    // A last step turning more than this is no travel: degenerate_velocity_keep applies along
    // every direction (a robot turning on the spot does not go on at its last walking speed).
    double degenerate_travel_turn = 3.0;  // [deg]
    // The spin hold (spin_hold.hpp): a degenerate scan whose fit turned at least this fast since
    // the last pose keeps the last position along every translation direction it did not observe
    // (the registration's unobserved ones; for a scan the observability check found degenerate,
    // every direction below observability.weak_information) instead of the motion model's: a
    // sensor spinning that fast is turning on the spot, not travelling. Not with wheel odometry
    // (it measures the translation). 0: off.
    double spin_rate = 45.0;  // [deg/s]
    // ... the larger of the fit's rate and the published steps' rate smoothed over this window
    // (a fit's rotation is noisy where its translation is unobserved).
    double spin_window = 0.5;  // [s]
    double yaw_search = 90.0;  // [deg] 0: no yaw search
    double yaw_step = 15.0;    // [deg]
    // The best of those guesses is probed again turned by +-yaw_refine (coarse to fine: a fit's
    // basin in yaw is a few degrees when its translation is off too). 0: not refined.
    double yaw_refine = 5.0;  // [deg]
    // Scans further apart than search_after are predicted holding the last heading (the last
    // step's translation in odometry axes, not turned with the turn rate) when, over the recent
    // scans that measured their rotation, the held heading's mean error was at most this times
    // the constant turn rate's (heading_skill.hpp: a handheld sensor's sparse keyframes swing
    // left and right). 0: always the constant turn rate.
    double heading_hold_ratio = 0.8;
    // Lost (no acceptable registration) for this long since the last tracked scan, sensor time:
    // the odometry ends its local maps and starts a new one at its best estimate (a new segment,
    // joined to the map later by a loop or by localisation).
    double restart_after = 0.5;  // [s]
    // Degenerate scans kept out of the map (their position along a weak direction is a guess)
    // this many in a row, each fit fixing no horizontal direction (what it constrains is within
    // 30 deg of the vertical: the ground's normal): the map holds nothing around the robot but
    // ground (it went on across open ground at a speed nothing measured), so its fits say nothing;
    // the odometry starts a new segment from this scan, as after being lost. 0: never.
    int restart_kept_out = 10;  // [scans]
    // No scan for longer than this (sensor time between two scans): a new segment at once, not a
    // fit to the old map (the robot may have been carried; a look-alike place of a repetitive site
    // fits as well as the right one). Longer than any gap a scan stream has in normal running
    // (keyframe streams of a fast car: 1-1.5 s). 0: off.
    double restart_gap = 2.0;  // [s]
    // ... and longer than this many times the stream's usual interval (the median of the last 10;
    // the first 3 intervals of a run are never a gap): a keyframe stream's pause while the robot
    // stands (hku-avia: 7.3 s before its second keyframe) or every 5th keyframe (2-3.4 s apart)
    // is no gap. 0: restart_gap alone decides.
    double restart_gap_cadence = 5.0;
};

// Local maps (Eq. 9): a box around an anchor; a new map starts when the sensor leaves the
// switch box; finished maps are handed out.
struct LocalMapConfig {
    double half_extent = 50.0;      // voxels within this of the anchor belong to it [m]
    double switch_distance = 20.0;  // sensor this far from the anchor (box): new map [m]
    int max_active_maps = 2;        // newest for registration, older ones still updated
};

struct KeyframeConfig {
    double distance = 1.0;  // [m] since the last keyframe
    double angle = 10.0;    // [deg] since the last keyframe
};

struct OdometryConfig {
    double voxel_size = 0.6;  // local map voxel edge g [m]
    // A coarse grid of coarse_voxel_factor * voxel_size in every local map; registration first
    // aligns on it (a wider basin for poor predictions), then on the fine grid. 0: no coarse grid.
    int coarse_voxel_factor = 3;
    // Initial guess: "time" (constant velocity), "frame" (the last motion once per frame, for
    // streams with irregular stamps such as keyframes) or "none" (the last pose).
    std::string prediction = "time";
    PreprocessConfig preprocess;
    VoxelConfig voxel;
    RegistrationConfig registration;
    TrackingConfig tracking;
    ObservabilityConfig observability;
    LocalMapConfig local_map;
    KeyframeConfig keyframe;
    int min_scan_points = 100;  // fewer registration points: frame skipped
    int threads = 1;            // worker threads for parallel loops (1: serial)
};

// The odometry's settings for a sensor preset: its row of common/core/sensor_preset.hpp (voxel
// size, ranges, sample grids, local-map extent, keyframe distance), the rest the defaults.
using common::SensorPreset;
OdometryConfig preset_config(SensorPreset preset);

// Calls v(key, field, rule) for every field of the config, by its dotted key as in YAML; the rule
// is the field's (common/core/config_check.hpp).
template <class Visitor>
void visit_fields(OdometryConfig& c, Visitor&& v) {
    using namespace common::rules;
    v("voxel_size", c.voxel_size, positive);
    v("prediction", c.prediction, one_of({"time", "frame", "none"}));
    v("coarse_voxel_factor", c.coarse_voxel_factor, zero_or_in(2, 16));
    v("min_scan_points", c.min_scan_points, at_least(6));
    v("threads", c.threads, at_least(1));
    registration::visit_fields(c.preprocess, "preprocess.", v);
    registration::visit_fields(c.voxel, "voxel.", v);
    registration::visit_fields(c.registration, "registration.", v);
    auto& t = c.tracking;
    v("tracking.min_inlier_fraction", t.min_inlier_fraction, unit);
    v("tracking.max_residual_ratio", t.max_residual_ratio, at_least(1));
    v("tracking.max_speed", t.max_speed, positive);
    v("tracking.max_angular_speed", t.max_angular_speed, positive);
    v("tracking.max_final_step_translation", t.max_final_step_translation, positive);
    v("tracking.max_final_step_rotation", t.max_final_step_rotation, positive);
    v("tracking.retry_residual_ratio", t.retry_residual_ratio, at_least(1));
    v("tracking.retry_inlier_ratio", t.retry_inlier_ratio, unit);
    v("tracking.retry_overlap_ratio", t.retry_overlap_ratio, unit);
    v("tracking.search_after", t.search_after, non_negative);
    v("tracking.recover_inlier_ratio", t.recover_inlier_ratio, unit);
    v("tracking.degenerate_velocity_keep", t.degenerate_velocity_keep, unit);
    v("tracking.degenerate_travel_keep", t.degenerate_travel_keep, unit);
    v("tracking.degenerate_travel_turn", t.degenerate_travel_turn, in_range(0, 180));
    v("tracking.spin_rate", t.spin_rate, non_negative);
    v("tracking.spin_window", t.spin_window, non_negative);
    v("tracking.yaw_search", t.yaw_search, in_range(0, 180));
    v("tracking.yaw_step", t.yaw_step, in_range(1, 90));
    v("tracking.yaw_refine", t.yaw_refine, in_range(0, 45));
    v("tracking.heading_hold_ratio", t.heading_hold_ratio, unit);
    v("tracking.restart_after", t.restart_after, non_negative);
    v("tracking.restart_gap", t.restart_gap, non_negative);
    v("tracking.restart_gap_cadence", t.restart_gap_cadence, non_negative);
    v("tracking.restart_kept_out", t.restart_kept_out, at_least(0));
    auto& o = c.observability;
    v("observability.weak_information", o.weak_information, unit);
    v("observability.slide_tolerance", o.slide_tolerance, non_negative);
    v("observability.slide_fraction", o.slide_fraction, unit);
    v("observability.search_step", o.search_step, positive);
    v("observability.margin_fraction", o.margin_fraction, non_negative);
    v("observability.min_margin", o.min_margin, non_negative);
    v("observability.first_step_range", o.first_step_range, non_negative);
    v("observability.min_support", o.min_support, non_negative);
    v("observability.min_contrast", o.min_contrast, at_least(1));
    v("observability.peak_width", o.peak_width, positive);
    v("observability.first_step_contrast", o.first_step_contrast, at_least(1));
    v("observability.basin_offset", o.basin_offset, non_negative);
    v("observability.basin_max_offset", o.basin_max_offset, non_negative);
    v("observability.basin_tolerance", o.basin_tolerance, non_negative);
    v("observability.degenerate_sigma_fraction", o.degenerate_sigma_fraction, non_negative);
    v("observability.degenerate_min_sigma", o.degenerate_min_sigma, non_negative);
    v("observability.weak_sigma_fraction", o.weak_sigma_fraction, non_negative);
    v("observability.weak_min_sigma", o.weak_min_sigma, non_negative);
    v("observability.covariance_scale", o.covariance_scale, at_least(1));
    v("observability.covariance_floor", o.covariance_floor, non_negative);
    auto& m = c.local_map;
    v("local_map.half_extent", m.half_extent, positive);
    v("local_map.switch_distance", m.switch_distance, positive);
    v("local_map.max_active_maps", m.max_active_maps, at_least(1));
    v("keyframe.distance", c.keyframe.distance, non_negative);
    v("keyframe.angle", c.keyframe.angle, non_negative);
}

// The first field that breaks its rule, then the rules across fields; the key as in YAML
// ("preprocess.max_range"). nullopt when valid. Odometry throws common::ConfigError under
// "odometry".
std::optional<common::ConfigProblem> validate(const OdometryConfig& config);

}  // namespace ltm::odometry
