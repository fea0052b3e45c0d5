#include "common/core/sensor_preset.hpp"

#include <stdexcept>

namespace ltm::common {
namespace {

// One row per preset (the columns in the order of SensorPresetRow):
//   name, sensor, simulator model,
//   rings, vertical fov [deg], horizontal fov [deg], descriptor height [m] (see the header),
//   odometry {voxel, coarse factor, min range, max range, map sample fraction, registration sample
//             fraction, local-map half extent, switch distance, keyframe distance, min points},
//   places {descriptor range, loop exclude recent [s], ... [keyframes], loop max distance, loop
//           cooldown, verify downsample, verify min inliers, verify coarse factor, loop max
//           correction translation},
//   localisation {off-map margin, feature max range}.
// clang-format off

// Velodyne HDL-64E as on the KITTI car (+2 to -24.8 deg): the defaults every module was tuned on.
constexpr SensorPresetRow kHdl64{
    "hdl64", "Velodyne HDL-64E", "hdl64e",
    64, 26.8, 360.0, 1.73,
    {0.6, 3, 2.5, 80.0, 0.3, 1.5, 50.0, 20.0, 1.0, 100},
    {80.0, 30.0, 50, 0.35, 2, 1.0, 400, 3, 8.0},
    {8.0, 40.0}};

// Velodyne VLP-32C (+15 to -25 deg): half the rings of an HDL-64E, the same geometry a little
// sparser.
constexpr SensorPresetRow kVlp32{
    "vlp32", "Velodyne VLP-32C", "vlp32c",
    32, 40.0, 360.0, 1.73,
    {0.6, 3, 1.5, 70.0, 0.3, 1.5, 45.0, 20.0, 1.0, 100},
    {80.0, 30.0, 50, 0.35, 2, 1.0, 400, 3, 8.0},
    {8.0, 40.0}};

// Velodyne VLP-16 (+15 to -15 deg): 16 rings 2 deg apart: finer voxels, and registration on a
// finer grid to keep enough points.
constexpr SensorPresetRow kVlp16{
    "vlp16", "Velodyne VLP-16", "vlp16",
    16, 30.0, 360.0, 1.73,
    {0.5, 3, 1.0, 60.0, 0.3, 1.0, 40.0, 15.0, 1.0, 100},
    {80.0, 30.0, 50, 0.35, 2, 1.0, 400, 3, 8.0},
    {8.0, 40.0}};

// Livox Avia type (a 70.4 deg circular field): a few thousand points a scan, ranges mostly under
// 40 m. Every point registers; the coarse grid (2 m) gives the basin that fast turns of a narrow
// view need. A narrow view sees a place again only heading the same way: a nearer, stricter loop
// search with fewer inliers. Mounted at 1 m (fast_turns).
constexpr SensorPresetRow kNarrow{
    "narrow", "Livox Avia type (non-repetitive, ~70 deg)", "livox_avia",
    0, 70.4, 70.4, 1.0,
    {0.5, 4, 0.5, 50.0, 0.2, 0.2, 40.0, 15.0, 0.5, 50},
    {40.0, 15.0, 20, 0.4, 4, 0.3, 200, 4, 4.0},
    {5.0, 30.0}};

// Ouster OS1-64 (+22.5 to -22.5 deg): 64 beams evenly over 45 deg (denser near the ground than an
// HDL-64E is far out), 0.3-120 m; mostly used on slower platforms and closer to structure.
constexpr SensorPresetRow kOs1_64{
    "os1-64", "Ouster OS1-64", "os1_64",
    64, 45.0, 360.0, 1.73,
    {0.5, 3, 1.0, 80.0, 0.3, 1.5, 45.0, 18.0, 1.0, 100},
    {80.0, 30.0, 50, 0.35, 2, 1.0, 400, 3, 8.0},
    {8.0, 40.0}};

// clang-format on

}  // namespace

const SensorPresetRow& sensor_preset_row(SensorPreset preset) {
    switch (preset) {
        case SensorPreset::kHdl64:
            return kHdl64;
        case SensorPreset::kVlp32:
            return kVlp32;
        case SensorPreset::kVlp16:
            return kVlp16;
        case SensorPreset::kNarrow:
            return kNarrow;
        case SensorPreset::kOs1_64:
            return kOs1_64;
    }
    // Only a value cast from outside the enumerators gets here.
    throw std::invalid_argument("not a sensor preset: " + std::to_string(int(preset)));
}

const char* to_string(SensorPreset preset) { return sensor_preset_row(preset).name; }

std::vector<std::string> sensor_preset_names() {
    std::vector<std::string> names;
    for (SensorPreset p : kSensorPresets) names.emplace_back(to_string(p));
    return names;
}

SensorPreset parse_sensor_preset(const std::string& name) {
    std::string known;
    for (SensorPreset p : kSensorPresets) {
        if (name == to_string(p)) return p;
        known += (known.empty() ? "" : ", ") + std::string(to_string(p));
    }
    throw std::invalid_argument("unknown sensor preset '" + name + "' (known: " + known + ")");
}

}  // namespace ltm::common
