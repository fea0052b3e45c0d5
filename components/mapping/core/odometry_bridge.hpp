#pragma once
// Between the odometry core's objects and the plain map data the mapping core consumes
// (odometry/core/local_map_export.hpp converts the odometry's maps and keyframes):
//   common::LocalMapData -> odometry::VoxelGrid (fine, and optionally coarse), the registration
//     target of loop verification, in the map's grid frame.
// The last one goes through the VoxelGrid's public API only (it has no voxel insertion): each
// usable voxel is re-created by integrating a few points on a small disc with the voxel's centre
// and normal, so centre, normal and usability are reproduced (stability becomes the configured
// initial value); other voxels get their centre only. The coarse grid fits planes to those discs.
// An exact VoxelGrid::from_data() in the odometry core would replace the disc trick.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "odometry/core/local_map.hpp"
#include "odometry/core/local_map_export.hpp"
#include "odometry/core/odometry.hpp"
#include "odometry/core/voxel_grid.hpp"

namespace ltm::mapping {

// odometry::LocalMap / Keyframe -> plain data: the odometry core's own conversions.
using odometry::to_keyframe_data;
using odometry::to_local_map_data;

struct RegistrationTarget {
    odometry::VoxelGrid fine;
    std::optional<odometry::VoxelGrid> coarse;
    // Both grids are in the local map's grid frame: T_anchor_lidar = T_anchor_grid * T_grid_lidar.
    Eigen::Isometry3d T_anchor_grid = Eigen::Isometry3d::Identity();
    std::size_t skipped_voxels = 0;  // centre not finite or outside its own cell
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// A voxel of `data` is usable when its normal is a unit vector and its planarity is at least
// `min_planarity`. coarse_factor: 0 (no coarse grid) or the coarse voxel size in voxels (>= 2).
RegistrationTarget rebuild_registration_target(const common::LocalMapData& data,
                                               double min_planarity, int coarse_factor);

}  // namespace ltm::mapping
