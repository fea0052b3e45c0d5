#pragma once
// Configuration of the LiDAR odometry (METHOD.md sections 1-2): one plain struct with defaults for
// a Velodyne HDL-64E, plus named presets for other sensors. No I/O in here: the adapter loads YAML.
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "common/core/sensor_preset.hpp"
#include "registration/core/registration_config.hpp"

namespace ltm::odometry {

using registration::PreprocessConfig;
using registration::RegistrationConfig;
using registration::VoxelConfig;

// Plausibility of a registration result against the prediction: beyond it, divergence.
struct DivergenceConfig {
    double max_translation_correction = 2.0;   // [m] away from the constant-velocity prediction
    double max_rotation_correction = 15.0;     // [deg]
    double max_final_step_translation = 0.05;  // unconverged and last step larger: diverged [m]
    double max_final_step_rotation = 0.5;      // [deg]
    // A result not converged, or with a residual RMS above this times the recent frames', is
    // retried from the last pose and the better of the two kept.
    double retry_residual_ratio = 1.5;
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
    DivergenceConfig divergence;
    LocalMapConfig local_map;
    KeyframeConfig keyframe;
    int min_scan_points = 100;  // fewer registration points: frame skipped
    int threads = 1;            // worker threads for parallel loops (1: serial)
};

// The odometry's settings for a sensor preset (common/core/sensor_preset.hpp).
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
    auto& d = c.divergence;
    v("divergence.max_translation_correction", d.max_translation_correction, positive);
    v("divergence.max_rotation_correction", d.max_rotation_correction, positive);
    v("divergence.max_final_step_translation", d.max_final_step_translation, positive);
    v("divergence.max_final_step_rotation", d.max_final_step_rotation, positive);
    v("divergence.retry_residual_ratio", d.retry_residual_ratio, at_least(1));
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
