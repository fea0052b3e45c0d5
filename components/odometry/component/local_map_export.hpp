#pragma once
// The odometry's local maps and keyframes as the plain data every other module reads.
#include "common/core/local_map_data.hpp"
#include "odometry/core/local_map.hpp"
#include "odometry/core/odometry.hpp"

namespace ltm::odometry {

// Voxel geometry stays on the odometry's lattice (the grid frame: odometry axes, origin at
// LocalMap::origin()); T_anchor_grid ties it to the anchor.
common::LocalMapData export_local_map(const LocalMap& map, bool finished, std::uint32_t revision);

// T_anchor_lidar from the keyframe's local map (identity anchor when the map is not active any more).
common::KeyframeData export_keyframe(const Keyframe& keyframe, std::uint64_t scan_index,
                                     const Eigen::Isometry3d& T_odom_anchor);

}  // namespace ltm::odometry
