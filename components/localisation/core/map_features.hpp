#pragma once
// A map's local features (ground samples with a local ScanContext++ each, places/core/
// local_features.hpp) made from its merged voxels: on a lattice of cells of `feature_cell`
// anchored at the frame's origin, each cell's samples from the voxel centres around it. A sample is
// a lattice point of the features' spacing: the same sample found from two cells is kept once.
// The whole map's on load (LocalisationMap), or (paged) only the cells near a global query's
// places from the local maps it read: a cell's samples depend on the voxels within its
// half-diagonal + the features' radius only, so both give a cell the same samples wherever the
// voxels there are the same.
#include <Eigen/Geometry>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "localisation/core/localisation_map.hpp"
#include "places/core/local_features.hpp"

namespace ltm::localisation {

// A cell holds the samples up to its half-diagonal from its centre (over the cell's side).
constexpr double kFeatureCellHalfDiagonal = 0.7072;

// Every cell holding a voxel; with `around`, only the cells whose centre is within `near`
// (horizontal) of one of its points.
places::LocalFeatures make_map_features(const std::vector<common::VoxelData>& voxels,
                                        const LocalisationMapConfig& config,
                                        const std::vector<Eigen::Vector3d>* around = nullptr,
                                        double near = 0.0);

}  // namespace ltm::localisation
