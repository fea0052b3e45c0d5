#include "mapping/core/mapper_config.hpp"

#include <cmath>
#include <sstream>

namespace ltm::mapping {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

Matrix6d diagonal_information(double sigma_t, double sigma_r_rad) {
    Matrix6d I = Matrix6d::Zero();
    I.diagonal().head<3>().setConstant(1.0 / (sigma_t * sigma_t));
    I.diagonal().tail<3>().setConstant(1.0 / (sigma_r_rad * sigma_r_rad));
    return I;
}

bool positive(double v) { return v > 0.0 && std::isfinite(v); }
bool non_negative(double v) { return v >= 0.0 && std::isfinite(v); }

}  // namespace

MapperConfig mapper_preset(common::SensorPreset preset) {
    MapperConfig c;
    if (preset == common::SensorPreset::kNarrow) {
        c.scan_context.max_range = 40.0;
        c.scan_context.sensor_height = 1.0;
        c.loop_detection.exclude_recent_seconds = 15.0;
        c.loop_detection.exclude_recent_keyframes = 20;
        c.loop_detection.max_distance = 0.4;
        c.verification.downsample = 0.3;
        c.verification.min_inliers = 200;
        c.verification.coarse_factor = 4;
        c.verification.max_correction_translation = 4.0;
        c.loop_cooldown_keyframes = 4;
    } else {
        c.scan_context.sensor_height = 1.73;  // KITTI's HDL-64E
    }
    return c;
}

std::string validate(const MapperConfig& c) {
    for (const std::string& e : {validate(c.scan_context, "mapping.scan_context"),
                                 validate(c.loop_detection, "mapping.loop_detection"),
                                 validate(c.verification, "mapping.verification"),
                                 validate(c.pose_graph, "mapping.pose_graph"),
                                 validate(c.global_map, "mapping.global_map")}) {
        if (!e.empty()) return e;
    }
    std::ostringstream e;
    const OdometryEdgeConfig& o = c.odometry_edge;
    const LoopEdgeConfig& l = c.loop_edge;
    if (!positive(o.sigma_translation)) {
        e << "mapping.odometry_edge.sigma_translation must be > 0 (got " << o.sigma_translation
          << ")";
    } else if (!non_negative(o.sigma_translation_per_m)) {
        e << "mapping.odometry_edge.sigma_translation_per_m must be >= 0 (got "
          << o.sigma_translation_per_m << ")";
    } else if (!positive(o.sigma_rotation)) {
        e << "mapping.odometry_edge.sigma_rotation must be > 0 (got " << o.sigma_rotation << ")";
    } else if (!non_negative(o.sigma_rotation_per_m)) {
        e << "mapping.odometry_edge.sigma_rotation_per_m must be >= 0 (got "
          << o.sigma_rotation_per_m << ")";
    } else if (!positive(l.sigma_translation)) {
        e << "mapping.loop_edge.sigma_translation must be > 0 (got " << l.sigma_translation << ")";
    } else if (!positive(l.sigma_rotation)) {
        e << "mapping.loop_edge.sigma_rotation must be > 0 (got " << l.sigma_rotation << ")";
    } else if (!positive(c.loop_consistency.translation) ||
               !non_negative(c.loop_consistency.translation_per_m)) {
        e << "mapping.loop_consistency.translation must be > 0 and translation_per_m >= 0";
    } else if (!positive(c.loop_consistency.rotation) ||
               !non_negative(c.loop_consistency.rotation_per_m)) {
        e << "mapping.loop_consistency.rotation must be > 0 and rotation_per_m >= 0";
    } else if (c.max_loops_per_keyframe < 1) {
        e << "mapping.max_loops_per_keyframe must be >= 1 (got " << c.max_loops_per_keyframe << ")";
    } else if (c.max_loops_per_anchor_pair < 0) {
        e << "mapping.max_loops_per_anchor_pair must be >= 0 (got " << c.max_loops_per_anchor_pair
          << ")";
    } else if (c.loop_cooldown_keyframes < 0) {
        e << "mapping.loop_cooldown_keyframes must be >= 0 (got " << c.loop_cooldown_keyframes
          << ")";
    }
    return e.str();
}

Matrix6d odometry_information(const OdometryEdgeConfig& c, double distance) {
    const double d = std::max(0.0, distance);
    return diagonal_information(c.sigma_translation + c.sigma_translation_per_m * d,
                                (c.sigma_rotation + c.sigma_rotation_per_m * d) * kDegToRad);
}

Matrix6d loop_information(const LoopEdgeConfig& c) {
    return diagonal_information(c.sigma_translation, c.sigma_rotation * kDegToRad);
}

}  // namespace ltm::mapping
