#include "common/core/sensor_preset.hpp"

#include <stdexcept>

namespace ltm::common {

namespace {
constexpr SensorPreset kAll[] = {SensorPreset::kHdl64, SensorPreset::kVlp32, SensorPreset::kVlp16,
                                 SensorPreset::kNarrow, SensorPreset::kOs1_64};
}  // namespace

const char* to_string(SensorPreset preset) {
    switch (preset) {
        case SensorPreset::kHdl64:
            return "hdl64";
        case SensorPreset::kVlp32:
            return "vlp32";
        case SensorPreset::kVlp16:
            return "vlp16";
        case SensorPreset::kNarrow:
            return "narrow";
        case SensorPreset::kOs1_64:
            return "os1-64";
    }
    return "?";
}

std::vector<std::string> sensor_preset_names() {
    std::vector<std::string> names;
    for (SensorPreset p : kAll) names.emplace_back(to_string(p));
    return names;
}

SensorPreset parse_sensor_preset(const std::string& name) {
    std::string known;
    for (SensorPreset p : kAll) {
        if (name == to_string(p)) return p;
        known += (known.empty() ? "" : ", ") + std::string(to_string(p));
    }
    throw std::invalid_argument("unknown sensor preset '" + name + "' (known: " + known + ")");
}

}  // namespace ltm::common
