#pragma once
// OdometryConfig from parameters (a launch config's `params:`, or a YAML file given to the
// benchmark): an optional `preset` (hdl64, vlp32, vlp16, narrow, os1-64; `auto` in the odometry
// component: decided on the first scans, common/core/sensor_detect.hpp) picks the base, every
// other key mirrors the struct (`voxel_size`, `preprocess.max_range`, ...). Unknown keys, wrong
// types and invalid values fail with file, line and key (the keys and rules: visit_fields in
// odometry_config.hpp).
#include <optional>
#include <string>

#include "odometry/core/odometry_config.hpp"
#include "runtime/parameters.hpp"

namespace ltm::odometry {

// The preset `params` names at `prefix.preset` (default `default_preset`); empty for `auto`.
// Throws common::ConfigError at the key when it names no preset.
std::optional<common::SensorPreset> load_odometry_preset(
    runtime::Parameters& params, const std::string& prefix = "",
    const std::string& default_preset = "hdl64");

// `preset`'s config with every odometry key of `params` applied (under `prefix.` when not empty),
// whatever `params` names as the preset. Throws common::ConfigError naming file, line and key.
OdometryConfig load_odometry_config_for(runtime::Parameters& params, const std::string& prefix,
                                        common::SensorPreset preset);

// Reads `preset` (default `default_preset`; `auto` is refused: a config is wanted now) and every
// odometry key of `params` (under `prefix.`
// when prefix is not empty). Throws common::ConfigError naming file, line and key.
OdometryConfig load_odometry_config(runtime::Parameters& params, const std::string& prefix = "",
                                    const std::string& default_preset = "hdl64");

// A YAML file (a tool's --config): the odometry keys at its top level or under `odometry:`; other
// keys are refused. `preset` when given must not be in the file too.
OdometryConfig load_odometry_config_file(const std::string& path, const std::string& preset = "");

}  // namespace ltm::odometry
