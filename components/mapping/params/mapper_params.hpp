#pragma once
// MapperConfig from parameters (the mapping component's `params:`, or a YAML file given to the
// SLAM benchmark): an optional `preset` (hdl64, vlp32, vlp16, narrow, os1-64; `auto`: the
// spinning sensors' settings, which hdl64, vlp32, vlp16 and os1-64 share) picks the base, every
// other key mirrors the struct (`scan_context.rings`, `verification.fine.max_iterations`, ...).
// Unknown keys, wrong types and invalid values fail with file, line and key (the keys and rules:
// visit_fields in mapper_config.hpp and the parts' headers).
#include <string>

#include "mapping/core/mapper_config.hpp"
#include "runtime/parameters.hpp"

namespace ltm::mapping {

// Reads `preset` (default `default_preset`), `scan_context.kind` (max_height or mean_variance,
// i.e. ScanContext++) and every other mapping key of `params` (under `prefix.` when prefix is not
// empty). Throws common::ConfigError naming file, line and key.
MapperConfig load_mapper_config(runtime::Parameters& params, const std::string& prefix = "",
                                const std::string& default_preset = "hdl64");

// A YAML file (a tool's --mapping-config): the mapping keys at its top level or under `mapping:`;
// other keys are refused. `preset` when given must not be in the file too.
MapperConfig load_mapper_config_file(const std::string& path, const std::string& preset = "");

}  // namespace ltm::mapping
