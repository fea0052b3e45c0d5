#pragma once
// The health of a voxel from its life record (METHOD.md section 5): how well its presence is
// established. A voxel hit by one scan may be noise or something passing; one hit by `full_after`
// scans or more is established. Map maintenance lowers health further (to 0) where it removed
// what a voxel held; localisation leaves out voxels below its min_health and weighs the others'
// stability by their health.
#include <algorithm>

#include "common/core/local_map_data.hpp"

namespace ltm::common {

// 0.25 for a voxel seen once, rising linearly to 1 at `full_after` observations; 0 for none.
inline float life_health(const VoxelLife& life, double full_after = 5.0) {
    if (life.observations == 0) return 0.0f;
    const double f = std::min(1.0, double(life.observations - 1) / std::max(1.0, full_after - 1));
    return float(0.25 + 0.75 * f);
}

}  // namespace ltm::common
