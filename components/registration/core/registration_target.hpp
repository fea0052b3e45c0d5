#pragma once
// The registration target of loop verification: a local map's plain data (common::LocalMapData)
// loaded voxel for voxel into the registration core's grids (VoxelGrid::from_data), the fine grid
// and optionally a coarse grid merged from it, both in the local map's grid frame.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>

#include "common/core/local_map_data.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::registration {

struct RegistrationTarget {
    registration::VoxelGrid fine;
    std::optional<registration::VoxelGrid> coarse;
    // Both grids are in the local map's grid frame: T_anchor_lidar = T_anchor_grid * T_grid_lidar.
    Eigen::Isometry3d T_anchor_grid = Eigen::Isometry3d::Identity();
    std::size_t skipped_voxels = 0;  // index out of range, centre not finite, or repeated
    // Its grids (bytes).
    std::size_t memory_bytes() const {
        return sizeof(RegistrationTarget) + fine.memory_bytes() +
               (coarse ? coarse->memory_bytes() : 0);
    }
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// A voxel of `data` is usable when its normal is a unit vector and its planarity is at least
// `min_planarity`. coarse_factor: 0 (no coarse grid) or the coarse voxel size in voxels (>= 2).
RegistrationTarget make_registration_target(const common::LocalMapData& data, double min_planarity,
                                            int coarse_factor);

}  // namespace ltm::registration
