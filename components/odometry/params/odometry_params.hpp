#pragma once
// OdometryConfig from parameters (a launch config's `params:`, or a YAML file given to the
// benchmark): an optional `preset` (hdl64, vlp32, vlp16, narrow) picks the base, every other key
// mirrors the struct (`voxel_size`, `preprocess.max_range`, ...). Unknown keys, wrong types and
// invalid values fail with file, line and key.
#include <string>

#include "odometry/core/odometry_config.hpp"
#include "runtime/parameters.hpp"

namespace ltm::odometry {

// Calls v(key, field) for every field of the config, by its dotted key.
template <class Visitor>
void visit_fields(OdometryConfig& c, Visitor&& v) {
    auto& p = c.preprocess;
    auto& x = c.voxel;
    auto& d = c.divergence;
    auto& m = c.local_map;
    v("voxel_size", c.voxel_size);
    v("prediction", c.prediction);
    v("coarse_voxel_factor", c.coarse_voxel_factor);
    v("min_scan_points", c.min_scan_points);
    v("threads", c.threads);
    v("preprocess.min_range", p.min_range);
    v("preprocess.max_range", p.max_range);
    v("preprocess.map_sample_fraction", p.map_sample_fraction);
    v("preprocess.registration_sample_fraction", p.registration_sample_fraction);
    v("preprocess.max_registration_points", p.max_registration_points);
    v("preprocess.deskew", p.deskew);
    v("voxel.min_points_for_normal", x.min_points_for_normal);
    v("voxel.min_planarity", x.min_planarity);
    v("voxel.min_extent", x.min_extent);
    v("voxel.max_points", x.max_points);
    v("voxel.initial_stability", x.initial_stability);
    registration::visit_fields(c.registration, "registration.", v);
    v("divergence.max_translation_correction", d.max_translation_correction);
    v("divergence.max_rotation_correction", d.max_rotation_correction);
    v("divergence.max_final_step_translation", d.max_final_step_translation);
    v("divergence.max_final_step_rotation", d.max_final_step_rotation);
    v("divergence.retry_residual_ratio", d.retry_residual_ratio);
    v("local_map.half_extent", m.half_extent);
    v("local_map.switch_distance", m.switch_distance);
    v("local_map.max_active_maps", m.max_active_maps);
    v("keyframe.distance", c.keyframe.distance);
    v("keyframe.angle", c.keyframe.angle);
}

// Reads `preset` (default `default_preset`) and every odometry key of `params` (under `prefix.`
// when prefix is not empty). Throws runtime::ConfigError naming file, line and key.
OdometryConfig load_odometry_config(runtime::Parameters& params, const std::string& prefix = "",
                                    const std::string& default_preset = "hdl64");

// A YAML file (a tool's --config): the odometry keys at its top level or under `odometry:`; other
// keys are refused. `preset` when given must not be in the file too.
OdometryConfig load_odometry_config_file(const std::string& path, const std::string& preset = "");

}  // namespace ltm::odometry
