#pragma once
// Search along a weakly observable direction (issue 27): where along it does the scan fit the
// map? The directional support of a pose counts the scan points whose IMLS normal sees the
// direction (|n.v| >= 0.5) weighted by the Geman-McClure kernel of their residual: the trunks,
// poles and wall ends that fix the position along a road, not the ground and the side surfaces
// that fit equally well anywhere along it. Coarse-to-fine: every `spacing` over the range, then
// every spacing / 4 around the best.
#include <Eigen/Geometry>
#include <vector>

#include "registration/core/imls.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::odometry {

struct DirectionalSupport {
    double support = 0.0;  // sum of kernel weights of the points seeing the direction
    int points = 0;        // points seeing the direction with a correspondence
};

// Of the scan `points` (LiDAR frame) at T_map_lidar, along the unit map direction v.
DirectionalSupport directional_support(const std::vector<Eigen::Vector3f>& points,
                                       const registration::VoxelGrid& grid,
                                       const registration::ImlsParams& imls,
                                       const Eigen::Isometry3d& T_map_lidar,
                                       const Eigen::Vector3d& v, double kernel);

struct Profile {
    std::vector<double> offsets;  // [m] along v from the start pose, ascending
    std::vector<double> support;
    double best_offset = 0.0;
    double best_support = 0.0;
    double rival_support = 0.0;  // the best support more than peak_width from the best
    int evaluations = 0;

    // Best over the rival (large when nothing else fits; 1: no preference).
    double contrast() const { return best_support / std::max(rival_support, 1.0); }
};

struct ProfileRequest {
    double from = 0.0, to = 0.0;  // [m] offsets along v searched
    double spacing = 0.5;         // [m] of the coarse pass
    double peak_width = 1.5;      // [m]
    double kernel = 0.2;          // Geman-McClure scale [m]
};

// The support at T_start translated by o v, o over [from, to]: coarse pass, then refined.
Profile search_along(const std::vector<Eigen::Vector3f>& points,
                     const registration::VoxelGrid& grid, const registration::ImlsParams& imls,
                     const Eigen::Isometry3d& T_start, const Eigen::Vector3d& v,
                     const ProfileRequest& request);

}  // namespace ltm::odometry
