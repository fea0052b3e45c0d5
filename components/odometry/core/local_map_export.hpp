#pragma once
// The odometry's local maps and keyframes as the plain data every other module reads
// (common/core/local_map_data.hpp). The grid frame is the odometry's map frame: odometry axes at
// LocalMap::origin(), so T_anchor_grid = T_odom_anchor^-1 * T_odom_map; voxels keep their lattice.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "odometry/core/local_map.hpp"
#include "odometry/core/odometry.hpp"

namespace ltm::odometry {

// Voxels without a usable plane get a zero normal.
common::LocalMapData to_local_map_data(const LocalMap& map, std::uint32_t revision, bool finished,
                                       const std::vector<double>& observation_times = {});

common::KeyframeData to_keyframe_data(const Keyframe& keyframe,
                                      const Eigen::Isometry3d& T_odom_anchor,
                                      std::uint64_t scan_index);

}  // namespace ltm::odometry
