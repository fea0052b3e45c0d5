#pragma once
// Synthetic local-map voxels on analytic surfaces, for the mesh tests: each lattice cell the
// surface crosses holds one voxel whose centre is the surface point nearest the cell's centre and
// whose normal is the surface normal on the side the sensor saw.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "common/core/ply_io.hpp"

namespace ltm::mesh::test {

// The plane n . x = offset inside the box [lo, hi] (n towards the sensor).
std::vector<common::VoxelData> plane_voxels(const Eigen::Vector3d& n, double offset,
                                            const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                            double voxel_size);

// A sphere seen from outside (normals outwards).
std::vector<common::VoxelData> sphere_voxels(const Eigen::Vector3d& centre, double radius,
                                             double voxel_size);

// A local map of those voxels (grid frame = anchor frame unless T_anchor_grid is given).
common::LocalMapData local_map(
    std::uint64_t id, const std::vector<common::VoxelData>& voxels, double voxel_size,
    const Eigen::Isometry3d& T_odom_anchor,
    const Eigen::Isometry3d& T_anchor_grid = Eigen::Isometry3d::Identity());

// Number of times the segment [a, b] crosses the mesh's triangles.
int crossings(const common::PlyMesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace ltm::mesh::test
