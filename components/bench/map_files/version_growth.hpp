#pragma once
// Where a site version's growth went against the version before it (issue 26, repeated ground):
// the keyframes each session stored, the voxels of every local map before and after (and the new
// local maps), the maintained voxels added and gone, the added ones split by the hits their
// history holds, their height above the lowest voxel of their 2 m column and whether the last
// session created them. Printed to stdout; a bench's tool, not a library.
#include <string>

#include "maintenance/core/maintenance_config.hpp"

namespace ltm::bench {

void print_growth(const std::string& before, const std::string& after,
                  const maintenance::MaintenanceConfig& config);

}  // namespace ltm::bench
