#pragma once
// Named sensor presets shared by every module that tunes itself to a LiDAR type (odometry,
// mapping, localisation): "hdl64" (Velodyne HDL-64E, the default), "vlp32", "vlp16", "narrow"
// (Livox Avia type, ~70 deg field of view) and "os1-64" (Ouster OS1-64, 360 deg, 45 deg vertical).
// Each module maps a preset to its own settings.
#include <string>
#include <vector>

namespace ltm::common {

enum class SensorPreset { kHdl64, kVlp32, kVlp16, kNarrow, kOs1_64 };

// Throws std::invalid_argument naming the known presets.
SensorPreset parse_sensor_preset(const std::string& name);
const char* to_string(SensorPreset preset);
std::vector<std::string> sensor_preset_names();

}  // namespace ltm::common
