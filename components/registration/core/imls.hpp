#pragma once
// The IMLS point-to-surface distance over voxel surfels (METHOD.md Eq. 3, 4, 6):
//   I(x) = sum_i w_i (x - c_i).n_i / sum_i w_i,  w_i = exp(-||x - c_i||^2 / h^2),
// over the usable voxels of the 3x3x3 block around x's voxel, and the projection y = x - I(x) n_x
// with n_x the normal of the nearest voxel centre. Normals are sign-aligned with n_x first (a
// voxel normal's sign is arbitrary across voxels). Beyond the paper: voxels whose normal disagrees
// with n_x (another surface, e.g. the wall next to a floor point) can be left out of the sum, so
// that corners do not bias the distance.
#include <Eigen/Core>
#include <cstdint>

#include "registration/core/voxel_grid.hpp"

namespace ltm::registration {

struct ImlsParams {
    float bandwidth = 1.0f;             // h [m]
    float max_distance = 1.5f;          // the nearest usable voxel centre must be closer [m]
    float min_normal_agreement = 0.0f;  // |n_i . n_x| below this: voxel i left out [0..1]
};

struct ImlsResult {
    float distance = 0.0f;                                 // I(x) [m]
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();      // n_x
    Eigen::Vector3f projection = Eigen::Vector3f::Zero();  // y = x - I(x) n_x
    float stability = 0.0f;                                // s of the nearest voxel
    std::uint32_t nearest = 0;                             // index of the nearest voxel
    int neighbours = 0;                                    // voxels in the sum
};

// x in the grid's frame (the map frame). False when no usable voxel is within reach.
bool imls_distance(const VoxelGrid& grid, const Eigen::Vector3f& x, const ImlsParams& params,
                   ImlsResult* result);

// The two halves of imls_distance, for callers that re-evaluate a point whose voxel did not
// change (the usable voxels of the block are then the same):
// the usable voxels of the 3x3x3 block around x's voxel (at most 27 written to `out`) ...
int usable_neighbours(const VoxelGrid& grid, const Eigen::Vector3f& x, std::uint32_t* out);
// ... and the distance from those voxels.
bool imls_from_neighbours(const std::vector<Surfel>& surfels, const std::uint32_t* neighbours,
                          int count, const Eigen::Vector3f& x, const ImlsParams& params,
                          ImlsResult* result);

}  // namespace ltm::registration
