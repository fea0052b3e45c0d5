#include "mapping/core/mapper_config.hpp"

#include <cmath>

namespace ltm::mapping {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

Matrix6d diagonal_information(double sigma_t, double sigma_r_rad) {
    Matrix6d I = Matrix6d::Zero();
    I.diagonal().head<3>().setConstant(1.0 / (sigma_t * sigma_t));
    I.diagonal().tail<3>().setConstant(1.0 / (sigma_r_rad * sigma_r_rad));
    return I;
}

}  // namespace

MapperConfig mapper_preset(common::SensorPreset preset) {
    const common::SensorPresetRow& row = common::sensor_preset_row(preset);
    const common::SensorPresetRow::Places& r = row.places;
    MapperConfig c;
    c.scan_context.max_range = r.descriptor_max_range;
    c.scan_context.sensor_height = row.descriptor_height;
    c.loop_detection.exclude_recent_seconds = r.loop_exclude_recent_s;
    c.loop_detection.exclude_recent_keyframes = r.loop_exclude_recent_keyframes;
    c.loop_detection.max_distance = r.loop_max_distance;
    c.verification.downsample = r.verify_downsample;
    c.verification.min_inliers = r.verify_min_inliers;
    c.verification.coarse_factor = r.verify_coarse_factor;
    c.verification.max_correction_translation = r.loop_max_correction_translation;
    c.loop_cooldown_keyframes = r.loop_cooldown_keyframes;
    // A spinning sensor's keyframe stands for a revisit whatever its heading (issue 26: a road
    // driven both ways stored two sets of keyframes, +4.3 MB on site_week's day 1).
    if (row.horizontal_fov_deg >= 360.0) c.long_term.keyframe_angle = 180.0;
    // Both descriptors see the same part of the scan.
    c.localisation_descriptor.max_range = c.scan_context.max_range;
    c.localisation_descriptor.min_range = c.scan_context.min_range;
    c.localisation_descriptor.sensor_height = c.scan_context.sensor_height;
    return c;
}

std::optional<common::ConfigProblem> validate(const MapperConfig& config) {
    common::ConfigChecker k;
    k.include(validate(config.scan_context), "scan_context.");
    k.include(validate(config.localisation_descriptor), "localisation_descriptor.");
    if (config.localisation_descriptor.kind != places::ScanContextKind::kMeanVariance) {
        k.include(common::ConfigProblem{"kind", "must be mean_variance (ScanContext++)"},
                  "localisation_descriptor.");
    }
    k.include(validate(config.loop_detection), "loop_detection.");
    k.include(validate(config.verification), "verification.");
    k.include(validate(config.pose_graph), "pose_graph.");
    k.include(validate(config.global_map), "global_map.");
    MapperConfig c = config;  // visit_own_fields takes a mutable config (loaders write through it)
    visit_own_fields(c, k);
    return k.problem();
}

Matrix6d odometry_information(const OdometryEdgeConfig& c, double distance) {
    const double d = std::max(0.0, distance);
    return diagonal_information(c.sigma_translation + c.sigma_translation_per_m * d,
                                (c.sigma_rotation + c.sigma_rotation_per_m * d) * kDegToRad);
}

Matrix6d loop_information(const LoopEdgeConfig& c) {
    return diagonal_information(c.sigma_translation, c.sigma_rotation * kDegToRad);
}

Matrix6d segment_break_information() { return diagonal_information(100.0, M_PI); }

bool is_segment_break(const map::PoseGraphEdge& edge) {
    return edge.kind == map::EdgeKind::kOdometry && edge.information == segment_break_information();
}

}  // namespace ltm::mapping
