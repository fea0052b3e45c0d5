#pragma once
// Ground removal on a region's voxels (METHOD.md section 5, before segmentation). Why not PCL's
// RANSAC plane (SACSegmentation): one plane does not fit sloped terrain, ramps or a road's camber
// over a 40 m region. Why not a morphological filter (PCL's ProgressiveMorphologicalFilter): it
// works on points and takes seconds a region. The voxels already carry a centre and a normal, so
// the test is local and cheap, in the spirit of Patchwork's per-bin ground fitting: a voxel is
// ground when it is within `height` of the lowest voxel of its column neighbourhood and its
// normal is within `max_tilt` of the vertical, or (without a plane: few points) its points are
// flat (z spread within `flatness`). The foot of a container, where its wall meets the ground,
// has neither, and leaves with the container.
#include <cstddef>

#include "maintenance/core/observation_map.hpp"

namespace ltm::maintenance {

// Sets or clears the kGround flag of every voxel; returns how many are ground.
std::size_t mark_ground(const GroundConfig& config, ObservationMap& map);

}  // namespace ltm::maintenance
