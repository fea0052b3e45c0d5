#pragma once
// Between the odometry core's objects and the plain map data the mapping core consumes:
//   odometry::LocalMap -> common::LocalMapData (the grid frame is the odometry's map frame: the
//     odometry axes at LocalMap::origin(), so T_anchor_grid = T_odom_anchor^-1 * T_odom_map);
//   odometry::Keyframe -> common::KeyframeData;
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
#include "odometry/core/odometry.hpp"
#include "odometry/core/voxel_grid.hpp"

namespace ltm::mapping {

common::LocalMapData to_local_map_data(const odometry::LocalMap& map, std::uint32_t revision,
                                       bool finished,
                                       const std::vector<double>& observation_times = {});

common::KeyframeData to_keyframe_data(const odometry::Keyframe& keyframe,
                                      const Eigen::Isometry3d& T_odom_anchor,
                                      std::uint64_t scan_index);

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
