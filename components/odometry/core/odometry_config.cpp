#include "odometry/core/odometry_config.hpp"

namespace ltm::odometry {

OdometryConfig preset_config(SensorPreset preset) {
    OdometryConfig c;  // the defaults are the HDL-64E preset (tuned on the KITTI snippets)
    switch (preset) {
        case SensorPreset::kHdl64:
            break;
        case SensorPreset::kVlp32:
            // Half the rings of an HDL-64E: the same geometry a little sparser.
            c.preprocess.min_range = 1.5;
            c.preprocess.max_range = 70.0;
            c.local_map.half_extent = 45.0;
            break;
        case SensorPreset::kVlp16:
            // 16 rings 2 deg apart: finer voxels, and registration on a finer grid to keep
            // enough points.
            c.voxel_size = 0.5;
            c.preprocess.min_range = 1.0;
            c.preprocess.max_range = 60.0;
            c.preprocess.registration_sample_fraction = 1.0;
            c.local_map.half_extent = 40.0;
            c.local_map.switch_distance = 15.0;
            break;
        case SensorPreset::kNarrow:
            // Livox Avia type: ~70 deg field of view, a few thousand points a scan, ranges mostly
            // under 40 m. Every point registers; the coarse grid (2 m) gives the basin that fast
            // turns of a narrow view need.
            c.voxel_size = 0.5;
            c.coarse_voxel_factor = 4;
            c.preprocess.min_range = 0.5;
            c.preprocess.max_range = 50.0;
            c.preprocess.map_sample_fraction = 0.2;
            c.preprocess.registration_sample_fraction = 0.2;
            c.local_map.half_extent = 40.0;
            c.local_map.switch_distance = 15.0;
            c.keyframe.distance = 0.5;
            c.min_scan_points = 50;
            break;
        case SensorPreset::kOs1_64:
            // Ouster OS1-64: 64 beams evenly over 45 deg (denser near the ground than an HDL-64E
            // is far out), 0.3-120 m; mostly used on slower platforms and closer to structure.
            c.voxel_size = 0.5;
            c.preprocess.min_range = 1.0;
            c.preprocess.max_range = 80.0;
            c.local_map.half_extent = 45.0;
            c.local_map.switch_distance = 18.0;
            break;
    }
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
    return k.problem();
}

}  // namespace ltm::odometry
