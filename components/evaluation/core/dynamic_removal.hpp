#pragma once
// Dynamic-object removal scores, as the DynamicMap benchmark (KTH-RPL, Zhang et al. 2023)
// defines them: every point of the ground-truth labelled map (all scans' points in the world
// frame, each labelled static or dynamic) counts as kept when the output map has a point within
// `match_distance` of it (the benchmark's export_eval_pcd, default 0.05 m), removed otherwise.
//   SA = static points kept / static points        [%]
//   DA = dynamic points removed / dynamic points   [%]
//   AA = sqrt(SA * DA), HA = 2 SA DA / (SA + DA)   [%]
// Per dynamic object (scans with labels): an object is a class and an instance id (the label's
// upper 16 bits; SemanticKITTI numbers instances per class, so moving car 1 and moving person 1
// are two objects); dynamic points with instance id 0 form one object per class. Its travel is
// the distance between the centroid of its points in the first frame it appears in and in the
// last (world frame). DA over the objects that travel at least `min_travel` tells removing moving
// objects apart from the cars labelled moving that stand
// almost still within the window.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "common/core/point_labels.hpp"

namespace ltm::eval {

struct DynamicRemovalConfig {
    double match_distance =
        0.05;                 // [m] a ground-truth point is kept if an output point is this near
    double min_travel = 1.0;  // [m] objects travelling this far count as moving objects
};

struct LabelledMap {
    std::vector<Eigen::Vector3f> points;  // world frame [m]
    std::vector<std::uint8_t> dynamic;    // 1 dynamic, 0 static, one per point
    // Filled by append_labelled_scan (empty for a map read without labels), one per point: the
    // raw label and the frame (scan number) the point comes from.
    std::vector<std::uint32_t> labels;
    std::vector<std::uint32_t> frames;
};

struct DynamicObject {
    std::uint16_t instance = 0;     // the label's upper 16 bits; 0: the class's points without one
    std::uint16_t label_class = 0;  // the label's lower 16 bits
    std::uint32_t first_frame = 0, last_frame = 0;
    std::size_t frames = 0;  // frames it appears in
    std::size_t points = 0, removed = 0;
    double travel = 0.0;       // [m] centroid in the first frame to centroid in the last
    double removed_pct = 0.0;  // removed / points [%]
};

struct DynamicRemovalResult {
    std::size_t static_points = 0, static_kept = 0;
    std::size_t dynamic_points = 0, dynamic_removed = 0;
    double sa_pct = 0.0, da_pct = 0.0, aa_pct = 0.0, ha_pct = 0.0;  // 0 where a class is empty

    // Per object, ordered by instance id then class (instance 0 last); empty when the
    // truth has no per-point labels.
    std::vector<DynamicObject> objects;
    // The static objects (class and instance id) that lost the most points, most first (at most
    // 10; travel and frames unset): where a method hurts SA.
    std::vector<DynamicObject> static_losses;
    // Over the objects that travel at least min_travel: their points, those removed, and
    // moving_da_pct = removed / points [%] (0 when there is none).
    std::size_t moving_objects = 0, moving_points = 0, moving_removed = 0;
    double moving_da_pct = 0.0;
};

// Adds one scan (sensor frame) to the ground-truth map: points transformed by T_world_sensor,
// labelled with is_dynamic_label(). Points farther than max_range [m] from the sensor are
// skipped when max_range > 0 (the benchmark keeps SemanticKITTI points within 50 m).
// `frame` is the scan's number (per-object first and last frame, travel).
// Returns false (map untouched) when labels.size() != cloud.size().
bool append_labelled_scan(const common::PointCloud& cloud, const std::vector<std::uint32_t>& labels,
                          const Eigen::Isometry3d& T_world_sensor, common::LabelScheme scheme,
                          bool changed_is_dynamic, double max_range, std::uint32_t frame,
                          LabelledMap& map);

DynamicRemovalResult evaluate_dynamic_removal(const LabelledMap& truth,
                                              const std::vector<Eigen::Vector3f>& output_map,
                                              const DynamicRemovalConfig& config = {});

}  // namespace ltm::eval
