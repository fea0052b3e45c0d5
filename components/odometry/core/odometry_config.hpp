#pragma once
// Configuration of the LiDAR odometry (METHOD.md sections 1-2): one plain struct with defaults for
// a Velodyne HDL-64E, plus named presets for other sensors. No I/O in here: the adapter loads YAML.
#include <stdexcept>
#include <string>
#include <vector>

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

class ConfigError : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

// Empty when valid; otherwise one line naming the first offending key (e.g.
// "odometry.voxel_size must be > 0 (got -1)").
std::string validate(const OdometryConfig& config);

}  // namespace ltm::odometry
