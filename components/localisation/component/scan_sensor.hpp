#pragma once
// The sensor the localisation's scans come from, and the settings it gives (the component's
// thread). `preset` named: its settings. `auto`: the preset this host's odometry component is
// named, else the one the first scans tell (common::SensorDetector): until then the spinning
// sensors' localiser and map settings (common::kAutoSpinningPreset) and no scan preprocessed; a
// narrow sensor then retunes them to the narrow preset's (Retune: the component's worker loads its
// map again before its first scan, and a site's versions are loaded with them). The scans are
// preprocessed as this host's odometry component runs (its preset and every key it is given), else
// as the preset says.
#include <optional>

#include "common/core/point_cloud.hpp"
#include "common/core/sensor_detect.hpp"
#include "localisation/core/localiser.hpp"
#include "registration/core/preprocess.hpp"
#include "runtime/component.hpp"

namespace ltm::localisation {

class ScanSensor {
  public:
    // Reads `preset` and the localiser's keys of the component's parameters (ConfigError at the
    // key); says in the log what it chose.
    explicit ScanSensor(runtime::ComponentContext& ctx);

    // The settings at start (auto and untold: the spinning sensors').
    common::SensorPreset preset() const { return preset_; }
    const LocaliserConfig& config() const { return config_; }

    // Told (named, or by the scans) and the scans' preprocessing made.
    bool ready() const { return told_ && preprocessor_.has_value(); }

    struct Retune {
        common::SensorPreset preset;
        LocaliserConfig config;
    };
    // A scan while not ready: true when the sensor is told now (or was); `retune` set when the
    // settings are no longer the start's.
    bool add(const common::PointCloud& cloud, std::optional<Retune>* retune);

    // The scans' preprocessing (made before ready() turns true; the worker's from then on).
    registration::Preprocessor& preprocessor() { return *preprocessor_; }

  private:
    runtime::ComponentContext& ctx_;
    std::optional<common::SensorPreset> named_;  // empty: auto
    common::SensorPreset preset_ = common::kAutoSpinningPreset;
    LocaliserConfig config_;
    std::optional<LocaliserConfig> narrow_config_;  // auto and untold: for a narrow sensor
    common::SensorDetector detector_;
    bool told_ = false;
    std::optional<registration::Preprocessor> preprocessor_;
};

}  // namespace ltm::localisation
