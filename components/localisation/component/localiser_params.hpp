#pragma once
// LocaliserConfig from parameters (the localisation component's `params:`): the sensor preset
// (hdl64, vlp32, vlp16, narrow, os1-64) picks the base, every other key mirrors the struct
// (`global.candidates`, `tracking.max_iterations`, `lost_after`, ...: visit_fields in
// localisation/core/localiser.hpp). Wrong types and invalid values fail with file, line and key;
// the host refuses the keys nobody read.
#include <optional>
#include <string>

#include "common/core/sensor_preset.hpp"
#include "localisation/core/localiser.hpp"
#include "runtime/parameters.hpp"

namespace ltm::localisation {

// Reads `preset` (default `default_preset`); throws ConfigError at that key when it is unknown.
common::SensorPreset load_sensor_preset(runtime::Parameters& params,
                                        const std::string& default_preset = "hdl64");

// Reads `preset` (default `default_preset`): empty for `auto` (the localisation component then
// takes the spinning sensors' settings, common::kAutoSpinningPreset, and preprocesses the scans
// as the first scans tell). Throws ConfigError at that key when it names no preset.
std::optional<common::SensorPreset> load_sensor_preset_or_auto(runtime::Parameters& params,
                                                               const std::string& default_preset);

// The preset's LocaliserConfig with every localiser key of `params` applied. Throws ConfigError
// naming file, line and key.
LocaliserConfig load_localiser_config(runtime::Parameters& params, common::SensorPreset preset);

}  // namespace ltm::localisation
