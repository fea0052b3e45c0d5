#include "odometry/core/odometry_config.hpp"

namespace ltm::odometry {

OdometryConfig preset_config(SensorPreset preset) {
    const common::SensorPresetRow::Odometry& r = common::sensor_preset_row(preset).odometry;
    OdometryConfig c;
    c.voxel_size = r.voxel_size;
    c.coarse_voxel_factor = r.coarse_voxel_factor;
    c.preprocess.min_range = r.min_range;
    c.preprocess.max_range = r.max_range;
    c.preprocess.map_sample_fraction = r.map_sample_fraction;
    c.preprocess.registration_sample_fraction = r.registration_sample_fraction;
    c.local_map.half_extent = r.local_map_half_extent;
    c.local_map.switch_distance = r.local_map_switch_distance;
    c.keyframe.distance = r.keyframe_distance;
    c.min_scan_points = r.min_scan_points;
    return c;
}

std::optional<common::ConfigProblem> validate(const OdometryConfig& config) {
    OdometryConfig c = config;  // visit_fields takes a mutable config (loaders write through it)
    common::ConfigChecker k;
    visit_fields(c, k);
    k.include(validate(c.preprocess), "preprocess.");  // the rules across their fields
    k.include(validate(c.voxel), "voxel.");
    const LocalMapConfig& m = c.local_map;
    k.require(m.switch_distance < m.half_extent, "local_map.switch_distance",
              "must be smaller than local_map.half_extent");
    k.require(m.half_extent / c.voxel_size < 500000.0, "local_map.half_extent",
              "must be under 500000 voxels (voxel_size) for the voxel keys");
    k.require(c.observability.basin_max_offset >= c.observability.basin_offset,
              "observability.basin_max_offset", "must be at least observability.basin_offset");
    return k.problem();
}

}  // namespace ltm::odometry
