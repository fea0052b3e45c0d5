#include "odometry/core/odometry_config.hpp"

#include <cmath>
#include <sstream>

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
            c.divergence.max_rotation_correction = 30.0;
            c.local_map.half_extent = 40.0;
            c.local_map.switch_distance = 15.0;
            c.keyframe.distance = 0.5;
            c.min_scan_points = 50;
            break;
    }
    return c;
}

namespace {

// Collects the first violated rule, naming the key as it appears in YAML.
class Checker {
  public:
    void positive(const char* key, double v) { check(key, std::isfinite(v) && v > 0, "> 0", v); }
    void non_negative(const char* key, double v) {
        check(key, std::isfinite(v) && v >= 0, ">= 0", v);
    }
    void unit(const char* key, double v) {
        check(key, std::isfinite(v) && v >= 0 && v <= 1, "in [0, 1]", v);
    }
    void at_least(const char* key, double v, double lo) {
        std::ostringstream rule;
        rule << ">= " << lo;
        check(key, std::isfinite(v) && v >= lo, rule.str(), v);
    }
    void rule(bool ok, const std::string& message) {
        if (!ok && error_.empty()) error_ = message;
    }
    const std::string& error() const { return error_; }

  private:
    void check(const char* key, bool ok, const std::string& rule, double v) {
        if (ok || !error_.empty()) return;
        std::ostringstream s;
        s << "odometry." << key << " must be " << rule << " (got " << v << ")";
        error_ = s.str();
    }
    std::string error_;
};

}  // namespace

std::string validate(const OdometryConfig& c) {
    Checker k;
    k.positive("voxel_size", c.voxel_size);
    k.rule(
        c.coarse_voxel_factor == 0 || (c.coarse_voxel_factor >= 2 && c.coarse_voxel_factor <= 16),
        "odometry.coarse_voxel_factor must be 0 or in [2, 16] (got " +
            std::to_string(c.coarse_voxel_factor) + ")");
    k.rule(c.prediction == "time" || c.prediction == "frame" || c.prediction == "none",
           "odometry.prediction must be time, frame or none (got '" + c.prediction + "')");
    const auto& p = c.preprocess;
    k.non_negative("preprocess.min_range", p.min_range);
    k.positive("preprocess.max_range", p.max_range);
    k.rule(p.max_range > p.min_range, "odometry.preprocess.max_range must exceed min_range");
    k.positive("preprocess.map_sample_fraction", p.map_sample_fraction);
    k.positive("preprocess.registration_sample_fraction", p.registration_sample_fraction);
    k.non_negative("preprocess.max_registration_points", p.max_registration_points);
    const auto& v = c.voxel;
    k.at_least("voxel.min_points_for_normal", v.min_points_for_normal, 3);
    k.unit("voxel.min_planarity", v.min_planarity);
    k.unit("voxel.min_extent", v.min_extent);
    k.at_least("voxel.max_points", v.max_points, v.min_points_for_normal);
    k.unit("voxel.initial_stability", v.initial_stability);
    const auto& r = c.registration;
    k.positive("registration.imls_bandwidth", r.imls_bandwidth);
    k.positive("registration.max_correspondence_distance", r.max_correspondence_distance);
    k.unit("registration.min_normal_agreement", r.min_normal_agreement);
    k.positive("registration.kernel_scale", r.kernel_scale);
    k.unit("registration.min_stability", r.min_stability);
    k.at_least("registration.max_iterations", r.max_iterations, 1);
    k.positive("registration.convergence_translation", r.convergence_translation);
    k.positive("registration.convergence_rotation", r.convergence_rotation);
    k.at_least("registration.min_correspondences", r.min_correspondences, 6);
    k.non_negative("registration.kernel_adaptive_factor", r.kernel_adaptive_factor);
    k.unit("registration.degeneracy_ratio", r.degeneracy_ratio);
    k.positive("registration.degeneracy_length", r.degeneracy_length);
    const auto& d = c.divergence;
    k.positive("divergence.max_translation_correction", d.max_translation_correction);
    k.positive("divergence.max_rotation_correction", d.max_rotation_correction);
    k.positive("divergence.max_final_step_translation", d.max_final_step_translation);
    k.positive("divergence.max_final_step_rotation", d.max_final_step_rotation);
    k.at_least("divergence.retry_residual_ratio", d.retry_residual_ratio, 1.0);
    const auto& m = c.local_map;
    k.positive("local_map.half_extent", m.half_extent);
    k.positive("local_map.switch_distance", m.switch_distance);
    k.rule(m.switch_distance < m.half_extent,
           "odometry.local_map.switch_distance must be smaller than local_map.half_extent");
    k.rule(m.half_extent / c.voxel_size < 500000.0,
           "odometry.local_map.half_extent is too many voxels for the voxel keys");
    k.at_least("local_map.max_active_maps", m.max_active_maps, 1);
    k.non_negative("keyframe.distance", c.keyframe.distance);
    k.non_negative("keyframe.angle", c.keyframe.angle);
    k.at_least("min_scan_points", c.min_scan_points, 6);
    k.at_least("threads", c.threads, 1);
    return k.error();
}

}  // namespace ltm::odometry
