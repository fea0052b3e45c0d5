#pragma once
// Configuration of the LiDAR odometry (METHOD.md sections 1-2): one plain struct with defaults for
// a Velodyne HDL-64E, plus named presets for other sensors. No I/O in here: the adapter loads YAML.
#include <stdexcept>
#include <string>
#include <vector>

namespace ltm::odometry {

// Pre-processing of a raw scan (Algorithm 1, before registration).
struct PreprocessConfig {
    double min_range = 2.5;                     // [m] closer points are dropped (vehicle, housing)
    double max_range = 80.0;                    // [m] farther points are dropped
    double map_sample_fraction = 0.3;           // grid for points updating the map [voxel_size]
    double registration_sample_fraction = 1.5;  // grid for registration points [voxel_size]
    int max_registration_points = 0;            // cap on registration points (0: no cap)
    bool deskew = true;                         // de-skew when the scan has per-point times
};

// The voxels of a local map (Eq. 1-2, 7).
struct VoxelConfig {
    int min_points_for_normal = 5;  // points a voxel needs before it has a normal
    double min_planarity = 0.4;     // 1 - l_min/l_mid below this: no usable plane [0..1]
    // The points must spread in two directions: sqrt(l_mid) below this fraction of the voxel size
    // is a line (one scan ring with range noise), not a plane [voxel_size].
    double min_extent = 0.1;
    double max_points = 60.0;        // running sums are scaled down past this weight
    double initial_stability = 0.5;  // stability of a voxel whose normal is new [0..1]
};

// Gauss-Newton over SE(3) on the IMLS point-to-surface residual (Eq. 3-6, 8).
struct RegistrationConfig {
    double imls_bandwidth = 1.0;               // h of the IMLS weights exp(-d^2/h^2) [voxel_size]
    double max_correspondence_distance = 1.5;  // nearest voxel centre farther: no residual [m]
    double min_normal_agreement = 0.7;    // |n_i . n_x| below this: voxel i not in the IMLS sum
    double kernel_scale = 0.1;            // Geman-McClure scale of the residual (floor) [m]
    double kernel_adaptive_factor = 3.0;  // scale at least this times the median |residual|
    bool stability_weighting = true;      // residual multiplied by the voxel's stability (Eq. 8)
    double min_stability = 0.1;           // floor of the stability weight [0..1]
    int max_iterations = 30;
    double convergence_translation = 5e-4;  // step below this (and rotation below): converged [m]
    double convergence_rotation = 5e-3;     // [deg]
    int min_correspondences = 50;           // fewer: the registration fails
    // A direction whose normalised information (weighted mean of (J.v)^2, rotation measured as
    // displacement at degeneracy_length) is below degeneracy_ratio is degenerate: reported, and
    // not updated (it stays at the prediction).
    double degeneracy_ratio = 0.01;
    double degeneracy_length = 5.0;  // [m]
};

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

// Named sensor presets: "hdl64", "vlp32", "vlp16", "narrow" (Livox Avia type, ~70 deg).
enum class SensorPreset { kHdl64, kVlp32, kVlp16, kNarrow };
OdometryConfig preset_config(SensorPreset preset);
// Throws ConfigError listing the known names.
SensorPreset parse_sensor_preset(const std::string& name);
std::vector<std::string> sensor_preset_names();

class ConfigError : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

// Empty when valid; otherwise one line naming the first offending key (e.g.
// "odometry.voxel_size must be > 0 (got -1)").
std::string validate(const OdometryConfig& config);

}  // namespace ltm::odometry
