#pragma once
// Dynamic-object removal scores, as the DynamicMap benchmark (KTH-RPL, Zhang et al. 2023)
// defines them: every point of the ground-truth labelled map (all scans' points in the world
// frame, each labelled static or dynamic) counts as kept when the output map has a point within
// `match_distance` of it (the benchmark's export_eval_pcd, default 0.05 m), removed otherwise.
//   SA = static points kept / static points        [%]
//   DA = dynamic points removed / dynamic points   [%]
//   AA = sqrt(SA * DA), HA = 2 SA DA / (SA + DA)   [%]
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "common/core/point_labels.hpp"

namespace ltm::eval {

struct DynamicRemovalConfig {
    double match_distance =
        0.05;  // [m] a ground-truth point is kept if an output point is this near
};

struct LabelledMap {
    std::vector<Eigen::Vector3f> points;  // world frame [m]
    std::vector<std::uint8_t> dynamic;    // 1 dynamic, 0 static, one per point
};

struct DynamicRemovalResult {
    std::size_t static_points = 0, static_kept = 0;
    std::size_t dynamic_points = 0, dynamic_removed = 0;
    double sa_pct = 0.0, da_pct = 0.0, aa_pct = 0.0, ha_pct = 0.0;  // 0 where a class is empty
};

// Adds one scan (sensor frame) to the ground-truth map: points transformed by T_world_sensor,
// labelled with is_dynamic_label(). Points farther than max_range [m] from the sensor are
// skipped when max_range > 0 (the benchmark keeps SemanticKITTI points within 50 m).
// Returns false (map untouched) when labels.size() != cloud.size().
bool append_labelled_scan(const common::PointCloud& cloud, const std::vector<std::uint32_t>& labels,
                          const Eigen::Isometry3d& T_world_sensor, common::LabelScheme scheme,
                          bool changed_is_dynamic, double max_range, LabelledMap& map);

DynamicRemovalResult evaluate_dynamic_removal(const LabelledMap& truth,
                                              const std::vector<Eigen::Vector3f>& output_map,
                                              const DynamicRemovalConfig& config = {});

}  // namespace ltm::eval
