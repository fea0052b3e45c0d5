#pragma once
// The sensor presets: one row per LiDAR type with every value a module tunes to it, read by the
// odometry (odometry::preset_config), the mapping (mapping::mapper_preset) and the localisation
// (localisation::localiser_preset, localisation_map_preset). Presets: "hdl64" (Velodyne HDL-64E,
// the default), "vlp32" (VLP-32C), "vlp16", "narrow" (Livox Avia type, ~70 deg field of view) and
// "os1-64" (Ouster OS1-64, 360 deg, 45 deg vertical).
// A new sensor: one enumerator, its row in sensor_preset.cpp (the switch there has no default,
// so the compiler asks for it) and its name in kSensorPresets; the modules follow the row.
#include <string>
#include <vector>

namespace ltm::common {

enum class SensorPreset { kHdl64, kVlp32, kVlp16, kNarrow, kOs1_64 };
inline constexpr SensorPreset kSensorPresets[] = {SensorPreset::kHdl64, SensorPreset::kVlp32,
                                                  SensorPreset::kVlp16, SensorPreset::kNarrow,
                                                  SensorPreset::kOs1_64};

struct SensorPresetRow {
    const char* name;             // the key in configs and on command lines: "hdl64"
    const char* sensor;           // what it is
    const char* simulator_model;  // the simulator's model of it (ltm_sim, bench_link.sh)

    // The sensor and how it is mounted.
    int rings;                  // beams (0: a non-repetitive pattern)
    double vertical_fov_deg;    // [deg]
    double horizontal_fov_deg;  // [deg] (360: spinning)
    // [m] added to z before the place descriptors' height bins (Scan Context's LIDAR_HEIGHT):
    // ground cells then stand above empty ones. Not the mount: 1.73 m (the HDL-64E's on the KITTI
    // car) for every spinning sensor. site_loop's VLP-32C is mounted at 1.0 m, and 1.0 here cost
    // loops (ltm_bench_slam --scenario site_loop --preset vlp32: 20 instead of 22, 2/3 revisits
    // closed instead of 3/3, ATE 0.083 instead of 0.069 m): the ground's cells became as empty
    // ones. Every saved map keeps the value it was made with (a map continued with another is
    // refused, naming the key).
    double descriptor_height;

    // The odometry (OdometryConfig).
    struct Odometry {
        double voxel_size;                    // [m] local-map voxel
        int coarse_voxel_factor;              // coarse registration grid [voxels]
        double min_range, max_range;          // [m] points used
        double map_sample_fraction;           // [voxel_size] grid of the points updating the map
        double registration_sample_fraction;  // [voxel_size] grid of the registration points
        double local_map_half_extent;         // [m]
        double local_map_switch_distance;     // [m]
        double keyframe_distance;             // [m]
        int min_scan_points;                  // fewer registration points: the scan is skipped
    } odometry;

    // Place recognition and the verification of a place (mapping's loops, localisation's global
    // localisation).
    struct Places {
        double descriptor_max_range;   // [m] scan context
        double loop_exclude_recent_s;  // [s] recent keyframes not searched for loops
        int loop_exclude_recent_keyframes;
        double loop_max_distance;  // descriptor distance
        int loop_cooldown_keyframes;
        double verify_downsample;  // [m]
        int verify_min_inliers;
        int verify_coarse_factor;                // [voxels]
        double loop_max_correction_translation;  // [m]
    } places;

    // The localisation.
    struct Localisation {
        double off_map_margin;     // [m]
        double feature_max_range;  // [m] local features
    } localisation;
};

// The preset's row (every preset has one).
const SensorPresetRow& sensor_preset_row(SensorPreset preset);

// Throws std::invalid_argument naming the known presets.
SensorPreset parse_sensor_preset(const std::string& name);
const char* to_string(SensorPreset preset);
std::vector<std::string> sensor_preset_names();

}  // namespace ltm::common
