#pragma once
// A search of horizontal offsets around a pose, by score alone (no registration): the offset at
// which most of a scan's points lie on a map surface. A registration's basin along a road lined
// with repeated things (a substation's bays, posts) is a metre or two: from an initial pose 2-5 m
// off it ends in the neighbouring minimum, a pose that fits the structure it reaches and leaves a
// fifth of the scan in the map's empty space (site_loop, another day's scans turned and shifted:
// three such poses 3.45 m and 58.8 m off were accepted, and most refusals on a 3-lap map were
// such minima while the true pose verified). The search puts the verification's start in the
// right basin; the verification decides.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "registration/core/imls.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::localisation {

struct TranslationSearchConfig {
    double radius = 5.0;  // offsets within this of the pose, horizontal [m] (0: no search)
    double step = 1.0;    // grid of the offsets [m]; a point is on a surface within 0.75 step
    int points = 300;     // scan points scored (evenly thinned)
    // Yaws tried about the pose at every offset [deg]: a guess from a descriptor is a few degrees
    // off too, and at 20 m a degree moves the structure by a third of a metre (site_loop, 3 laps,
    // another day's scans turned: refusals whose best guess was 3.9-5.6 m and 3-4 deg off).
    // The global localiser turns the guesses so only when none of them verified
    // (GlobalLocaliser::search_around).
    std::vector<double> yaw_offsets = {0.0};
    // Run when no initial pose verified, or the best verified one has an inlier fraction below
    // this (a fit with many points off is the sign of a neighbouring minimum).
    double below_inlier_fraction = 0.8;
};

template <class Visitor>
void visit_fields(TranslationSearchConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "radius", c.radius, non_negative);
    v(prefix + "step", c.step, positive);
    v(prefix + "points", c.points, at_least(10));
    v(prefix + "yaw_offsets", c.yaw_offsets, not_empty);
    v(prefix + "below_inlier_fraction", c.below_inlier_fraction, unit);
}

struct TranslationSearchResult {
    Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();  // the best offset applied
    double share = 0.0;           // of the points on a surface there
    double share_at_start = 0.0;  // ... and at the pose itself
    double offset = 0.0;          // [m]
    double yaw = 0.0;             // of the best offset [deg]
    int scored = 0;               // poses scored (offsets x yaws, the start included)
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// points: the scan in its LiDAR frame (thinned to config.points here); grid: the map's fine
// voxels in the map frame. Ties go to the smaller offset.
TranslationSearchResult search_translation(const std::vector<Eigen::Vector3f>& points,
                                           const registration::VoxelGrid& grid,
                                           const registration::ImlsParams& imls,
                                           const Eigen::Isometry3d& T_map_lidar,
                                           const TranslationSearchConfig& config);

}  // namespace ltm::localisation
