#pragma once
// Configuration of the registration core (METHOD.md sections 1-2): scan pre-processing, the voxels
// of a map and the IMLS Gauss-Newton registration. Plain structs with defaults for a Velodyne
// HDL-64E; the odometry, the loop verification and the localisation each hold their own copies.

#include <optional>
#include <string>

#include "common/core/config_check.hpp"

namespace ltm::registration {

// Pre-processing of a raw scan (Algorithm 1, before registration).
struct PreprocessConfig {
    double min_range = 2.5;                     // [m] closer points are dropped (vehicle, housing)
    double max_range = 80.0;                    // [m] farther points are dropped
    double map_sample_fraction = 0.3;           // grid for points updating the map [voxel_size]
    double registration_sample_fraction = 1.5;  // grid for registration points [voxel_size]
    int max_registration_points = 0;            // cap on registration points (0: no cap)
    bool deskew = true;                         // de-skew when the scan has per-point times
};

// The voxels of a local map (Eq. 1-2, 7).
struct VoxelConfig {
    int min_points_for_normal = 5;  // points a voxel needs before it has a normal
    double min_planarity = 0.4;     // 1 - l_min/l_mid below this: no usable plane [0..1]
    // The points must spread in two directions: sqrt(l_mid) below this fraction of the voxel size
    // is a line (one scan ring with range noise), not a plane [voxel_size].
    double min_extent = 0.1;
    double max_points = 60.0;        // running sums are scaled down past this weight
    double initial_stability = 0.5;  // stability of a voxel whose normal is new [0..1]
};

// Gauss-Newton over SE(3) on the IMLS point-to-surface residual (Eq. 3-6, 8).
struct RegistrationConfig {
    double imls_bandwidth = 1.0;               // h of the IMLS weights exp(-d^2/h^2) [voxel_size]
    double max_correspondence_distance = 1.5;  // nearest voxel centre farther: no residual [m]
    double min_normal_agreement = 0.7;    // |n_i . n_x| below this: voxel i not in the IMLS sum
    double kernel_scale = 0.1;            // Geman-McClure scale of the residual (floor) [m]
    double kernel_adaptive_factor = 3.0;  // scale at least this times the median |residual|
    bool stability_weighting = true;      // residual multiplied by the voxel's stability (Eq. 8)
    double min_stability = 0.1;           // floor of the stability weight [0..1]
    int max_iterations = 30;
    double convergence_translation = 5e-4;  // step below this (and rotation below): converged [m]
    double convergence_rotation = 5e-3;     // [deg]
    int min_correspondences = 50;           // fewer: the registration fails
    double inlier_distance =
        0.2;  // |residual| under this: an inlier (fit quality, not weights) [m]
    // A direction whose normalised information (weighted mean of (J.v)^2, rotation measured as
    // displacement at degeneracy_length) is below degeneracy_ratio is degenerate: reported, and
    // not updated (it stays at the prediction).
    double degeneracy_ratio = 0.01;
    double degeneracy_length = 5.0;  // [m]
};

// visit_fields: calls v(key, field, rule) for every field of a config, keys under `prefix`
// ("registration."); the rule is the field's (common/core/config_check.hpp). Loaders read the
// fields through it, validate() checks them with it.
template <class Visitor>
void visit_fields(PreprocessConfig& p, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "min_range", p.min_range, non_negative);
    v(prefix + "max_range", p.max_range, positive);
    v(prefix + "map_sample_fraction", p.map_sample_fraction, positive);
    v(prefix + "registration_sample_fraction", p.registration_sample_fraction, positive);
    v(prefix + "max_registration_points", p.max_registration_points, non_negative);
    v(prefix + "deskew", p.deskew, unchecked);
}

template <class Visitor>
void visit_fields(VoxelConfig& x, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "min_points_for_normal", x.min_points_for_normal, at_least(3));
    v(prefix + "min_planarity", x.min_planarity, unit);
    v(prefix + "min_extent", x.min_extent, unit);
    v(prefix + "max_points", x.max_points, positive);  // and >= min_points_for_normal
    v(prefix + "initial_stability", x.initial_stability, unit);
}

template <class Visitor>
void visit_fields(RegistrationConfig& r, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "imls_bandwidth", r.imls_bandwidth, positive);
    v(prefix + "max_correspondence_distance", r.max_correspondence_distance, positive);
    v(prefix + "min_normal_agreement", r.min_normal_agreement, unit);
    v(prefix + "kernel_scale", r.kernel_scale, positive);
    v(prefix + "stability_weighting", r.stability_weighting, unchecked);
    v(prefix + "min_stability", r.min_stability, unit);
    v(prefix + "max_iterations", r.max_iterations, at_least(1));
    v(prefix + "convergence_translation", r.convergence_translation, positive);
    v(prefix + "convergence_rotation", r.convergence_rotation, positive);
    v(prefix + "min_correspondences", r.min_correspondences, at_least(6));
    v(prefix + "kernel_adaptive_factor", r.kernel_adaptive_factor, non_negative);
    v(prefix + "inlier_distance", r.inlier_distance, positive);
    v(prefix + "degeneracy_ratio", r.degeneracy_ratio, unit);
    v(prefix + "degeneracy_length", r.degeneracy_length, positive);
}

// The first field that breaks its rule, then the rules across fields; keys relative to the
// config ("max_range"). nullopt when valid.
std::optional<common::ConfigProblem> validate(const PreprocessConfig& config);
std::optional<common::ConfigProblem> validate(const VoxelConfig& config);
std::optional<common::ConfigProblem> validate(const RegistrationConfig& config);

}  // namespace ltm::registration
