#pragma once
// OdometryConfig from parameters (a launch config's `params:`, or a YAML file given to the
// benchmark): an optional `preset` (hdl64, vlp32, vlp16, narrow, os1-64) picks the base, every
// other key mirrors the struct (`voxel_size`, `preprocess.max_range`, ...). Unknown keys, wrong
// types and invalid values fail with file, line and key (the keys and rules: visit_fields in
// odometry_config.hpp).
#include <string>

#include "odometry/core/odometry_config.hpp"
#include "runtime/parameters.hpp"

namespace ltm::odometry {

// Reads `preset` (default `default_preset`) and every odometry key of `params` (under `prefix.`
// when prefix is not empty). Throws common::ConfigError naming file, line and key.
OdometryConfig load_odometry_config(runtime::Parameters& params, const std::string& prefix = "",
                                    const std::string& default_preset = "hdl64");

// A YAML file (a tool's --config): the odometry keys at its top level or under `odometry:`; other
// keys are refused. `preset` when given must not be in the file too.
OdometryConfig load_odometry_config_file(const std::string& path, const std::string& preset = "");

}  // namespace ltm::odometry
