#pragma once
// MapperConfig from parameters (the mapping component's `params:`, or a YAML file given to the
// SLAM benchmark): an optional `preset` (hdl64, vlp32, vlp16, narrow) picks the base, every other
// key mirrors the struct (`scan_context.rings`, `verification.fine.max_iterations`, ...). Unknown
// keys, wrong types and invalid values fail with file, line and key.
#include <string>

#include "mapping/core/mapper_config.hpp"
#include "registration/core/registration_config.hpp"
#include "runtime/parameters.hpp"

namespace ltm::mapping {

// Calls v(key, field) for every field of the config except the Scan Context kind (an enum: read
// as a string by load_mapper_config), by its dotted key.
template <class Visitor>
void visit_fields(MapperConfig& c, Visitor&& v) {
    auto& s = c.scan_context;
    v("scan_context.rings", s.rings);
    v("scan_context.sectors", s.sectors);
    v("scan_context.max_range", s.max_range);
    v("scan_context.min_range", s.min_range);
    v("scan_context.sensor_height", s.sensor_height);
    v("scan_context.empty_bin_cost", s.empty_bin_cost);
    v("scan_context.shift_search_radius", s.shift_search_radius);
    auto& d = c.loop_detection;
    v("loop_detection.candidates", d.candidates);
    v("loop_detection.max_distance", d.max_distance);
    v("loop_detection.exclude_recent_keyframes", d.exclude_recent_keyframes);
    v("loop_detection.exclude_recent_seconds", d.exclude_recent_seconds);
    v("loop_detection.max_results", d.max_results);
    v("loop_detection.rebuild_every", d.rebuild_every);
    auto& r = c.verification;
    v("verification.coarse_factor", r.coarse_factor);
    registration::visit_fields(r.coarse, "verification.coarse.", v);
    registration::visit_fields(r.fine, "verification.fine.", v);
    v("verification.min_planarity", r.min_planarity);
    v("verification.downsample", r.downsample);
    v("verification.max_points", r.max_points);
    v("verification.yaw_offsets", r.yaw_offsets);
    v("verification.inlier_distance", r.inlier_distance);
    v("verification.min_inliers", r.min_inliers);
    v("verification.min_inlier_fraction", r.min_inlier_fraction);
    v("verification.max_inlier_rms", r.max_inlier_rms);
    v("verification.min_structure_inlier_ratio", r.min_structure_inlier_ratio);
    v("verification.min_structure_points", r.min_structure_points);
    v("verification.refuse_degenerate", r.refuse_degenerate);
    v("verification.max_correction_translation", r.max_correction_translation);
    v("verification.max_correction_rotation", r.max_correction_rotation);
    v("verification.cache_size", r.cache_size);
    auto& g = c.pose_graph;
    v("pose_graph.loop_loss", g.loop_loss);
    v("pose_graph.loop_loss_scale", g.loop_loss_scale);
    v("pose_graph.max_iterations", g.max_iterations);
    v("pose_graph.outlier_translation", g.outlier_translation);
    v("pose_graph.outlier_rotation", g.outlier_rotation);
    v("pose_graph.max_outlier_rounds", g.max_outlier_rounds);
    auto& o = c.odometry_edge;
    v("odometry_edge.sigma_translation", o.sigma_translation);
    v("odometry_edge.sigma_translation_per_m", o.sigma_translation_per_m);
    v("odometry_edge.sigma_rotation", o.sigma_rotation);
    v("odometry_edge.sigma_rotation_per_m", o.sigma_rotation_per_m);
    v("loop_edge.sigma_translation", c.loop_edge.sigma_translation);
    v("loop_edge.sigma_rotation", c.loop_edge.sigma_rotation);
    auto& k = c.loop_consistency;
    v("loop_consistency.translation", k.translation);
    v("loop_consistency.translation_per_m", k.translation_per_m);
    v("loop_consistency.rotation", k.rotation);
    v("loop_consistency.rotation_per_m", k.rotation_per_m);
    auto& m = c.global_map;
    v("global_map.voxel_size", m.voxel_size);
    v("global_map.with_normal_only", m.with_normal_only);
    v("global_map.min_planarity", m.min_planarity);
    v("global_map.min_point_count", m.min_point_count);
    v("max_loops_per_keyframe", c.max_loops_per_keyframe);
    v("loop_cooldown_keyframes", c.loop_cooldown_keyframes);
    v("verify_from_graph", c.verify_from_graph);
    v("max_loops_per_anchor_pair", c.max_loops_per_anchor_pair);
    v("keep_keyframe_points", c.keep_keyframe_points);
}

// Reads `preset` (default `default_preset`), `scan_context.kind` (max_height or mean_variance,
// i.e. ScanContext++) and every other mapping key of `params` (under `prefix.` when prefix is not
// empty). Throws runtime::ConfigError naming file, line and key.
MapperConfig load_mapper_config(runtime::Parameters& params, const std::string& prefix = "",
                                const std::string& default_preset = "hdl64");

// A YAML file (a tool's --mapping-config): the mapping keys at its top level or under `mapping:`;
// other keys are refused. `preset` when given must not be in the file too.
MapperConfig load_mapper_config_file(const std::string& path, const std::string& preset = "");

}  // namespace ltm::mapping
