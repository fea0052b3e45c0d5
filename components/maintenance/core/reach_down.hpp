#pragma once
// What stands under a removed voxel goes with it (change.reach_down): an object's lowest part
// near the ground, which a session's rays rarely pass through (they hit the ground just before or
// after it, or what stands in between), keeps its old history (static) while the part above it is
// seen through and removed. Walking down the column of every voxel a pass removes that an
// earlier session made, a voxel goes too when an earlier session made it and this session
// neither hit it nor viewed it; the walk stops at an empty cell, a ground voxel (kGround) or a
// voxel this session saw (its own verdict stands), and at most reach_down metres below.
#include <cstdint>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"
#include "maintenance/core/observation_map.hpp"

namespace ltm::maintenance {

// `remove`: by voxel, what the pass removes so far (ground flags set); the voxels it adds are
// set there too and returned, in the order found.
std::vector<std::uint32_t> reach_down(const MaintenanceConfig& config, const ObservationMap& map,
                                      double session_start, std::vector<bool>* remove);

}  // namespace ltm::maintenance
