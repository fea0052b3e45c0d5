#pragma once
// Observability of a registration's translation (issue 27): along which directions the fit's own
// normal equations fix the position, and whether the motion since the last scan is one the fit
// could have seen.
//
// The criterion: the translation information with the rotation marginalised out (the Schur
// complement S = H_tt - H_tr H_rr^-1 H_rt of the fit's Gauss-Newton Hessian H = sum w J^T J,
// perturbation [dt; dr]) divided by the total weight trace(H_tt) = sum w (|n| = 1). An eigenvalue
// of that normalised S is the weighted mean of (n.v)^2 over the correspondences, the rotation
// free to absorb what it can: 1/3 per axis when the normals point every way, 0 along a corridor.
// A direction whose eigenvalue is below `weak_information` is weak: a fit moves along it only as
// far as the few points that see it pull, and from a start a few metres off it stays there (the
// ground and the side surfaces fit just as well). Its position comes from a search of the
// directional support along it (step_search.hpp), or from the motion model.
#include <Eigen/Core>

#include "registration/core/se3.hpp"

namespace ltm::odometry {

struct ObservabilityConfig {
    // Normalised marginal translation information below this: a weak direction (about 10 % of
    // the 1/3 of an isotropic scene).
    double weak_information = 0.04;
    // Along a weak direction, a fit whose step differs from the prediction's by more than
    // slide_tolerance + slide_fraction * |predicted step|, or a predicted step of at least
    // search_step, is searched (below, the step is within the fit's basin: trusted).
    double slide_tolerance = 0.3;  // [m]
    double slide_fraction = 0.05;
    double search_step = 1.0;  // [m]
    // The search along a weak direction: from the fit and the prediction, margin_fraction of the
    // predicted step (at least min_margin) on either side, support evaluated every voxel_size,
    // then refined around the best.
    double margin_fraction = 0.3;
    double min_margin = 2.0;  // [m]
    // The first step of a run (no velocity yet, the prediction is no motion) and the scan after
    // a degenerate one (its velocity is a guess): searched this far either side [m].
    double first_step_range = 15.0;
    // The best position is observable when its support (Geman-McClure weighted points whose
    // normal sees the direction) is at least min_support and at least min_contrast times the
    // best support more than peak_width from it; else the position along the direction is the
    // motion model's and the scan is degenerate.
    double min_support = 8.0;
    double min_contrast = 2.0;
    double peak_width = 1.5;  // [m]
    // The first step of a run in a scene constrained every way (not weak): searched along the
    // sensor's forward axis from the prediction, a peak this distinct moves it.
    double first_step_contrast = 1.3;
    // A weak direction whose search found no distinct peak (or whose peak's fit was no better)
    // is still observed when the fit has a basin there: fits started `offset` either side of it
    // along the direction both come back to within basin_tolerance of it. The offset is the
    // fit's disagreement with the prediction, at least basin_offset, and after a degenerate scan
    // (the prediction a guess) at least weak_sigma_fraction of the expected step (which needs a
    // speed measured in a scan constrained every way); over basin_max_offset, or on the first
    // step of a run, it is not tried. A fit that stays where it started (a corridor; the ground
    // and roadsides of a tree-lined road) fails it; a narrow sensor's fit among the few surfaces
    // that see the direction passes (hku-avia handheld: information 0.01-0.04 along it, fits
    // back to within 0-6 mm from 0.5 m, corridor fits stay 0.2-0.5 m off). basin_offset 0: off.
    double basin_offset = 0.5;      // [m]
    double basin_max_offset = 1.5;  // [m]
    double basin_tolerance = 0.1;   // [m]
    // The published covariance is inflated along every weak direction by a standard deviation
    // of a fraction of the expected step (the larger of the predicted step and the speed last
    // measured in a scene constrained every way, times the time since the last scan): along a
    // weak direction the fit stays near where it started, so its error is the prediction's,
    // which is the whole step when the velocity there has died out (a corridor). Measured on
    // the hard cases: such steps are off by up to 100 % of the step, hence 0.5 (3 sigma = 1.5
    // steps). A degenerate scan (the motion model stood in): degenerate_sigma_fraction, at least
    // degenerate_min_sigma [m]; a weak direction the fit was trusted along (a small step it agreed
    // with): weak_sigma_fraction, at least weak_min_sigma [m]. A direction whose position the
    // search along it found (a distinct peak) is not inflated.
    double degenerate_sigma_fraction = 0.5;
    double degenerate_min_sigma = 0.3;
    double weak_sigma_fraction = 0.5;
    double weak_min_sigma = 0.05;
    // The published covariance of a registered scan: sigma^2 H^-1 times covariance_scale, plus
    // covariance_floor^2 on each position axis (the fit's own statistics ignore correlated
    // points and the map's own error).
    double covariance_scale = 4.0;
    double covariance_floor = 0.02;  // [m]
};

struct Observability {
    Eigen::Vector3d information = Eigen::Vector3d::Zero();     // normalised, ascending
    Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();  // unit columns, odometry axes
    int constrained = 0;  // directions at or above weak_information (0..3)

    Eigen::Vector3d weakest() const { return directions.col(0); }
    bool weak() const { return constrained < 3; }
};

// From the fit's Hessian (sum w J^T J, [dt; dr], map axes = odometry axes up to the local map's
// rotation, which the caller applies).
Observability translation_observability(const registration::Matrix6d& hessian,
                                        double weak_information);

// The published covariance of a registered scan (see ObservabilityConfig).
registration::Matrix6d honest_covariance(const registration::Matrix6d& fit_covariance,
                                         const ObservabilityConfig& config);

// Adds sigma^2 u u^T to the position block of `covariance` for every weak direction u of `o`
// (rotated into odometry axes by R_odom_map) that is not within about 25 deg of `fixed` (a unit
// direction whose position a search found; zero: none).
void inflate_weak(const Observability& o, const Eigen::Matrix3d& R_odom_map,
                  const Eigen::Vector3d& fixed, double sigma, registration::Matrix6d* covariance);

}  // namespace ltm::odometry
