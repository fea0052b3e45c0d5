#pragma once
// The dense surface of one local map (METHOD.md section 4, Eq. 11): every voxel with a normal
// writes its point-to-plane signed distance sdf(q) = n . (q - c) into the grid points q near it
// (within the truncation along n and `support` voxel sizes across it), weighted like the
// odometry's implicit surface (Eq. 4); the weighted mean per grid point is a narrow-band OpenVDB
// float grid, meshed by marching cubes (openvdb::tools::VolumeToMesh, adaptivity 0). Only cells
// whose eight corners all have a value are surfaced: a surface ends where its support ends
// instead of closing against the band's edge. Not VDBFusion's ray casting: nothing is integrated
// along beams, so free space is never carved and a scan costs nothing here (the voxels exist
// already). OpenVDB is used in sdf_mesher.cpp only.
#include <cstddef>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "common/core/ply_io.hpp"
#include "mesh/core/mesh_config.hpp"

namespace ltm::mesh {

struct SdfStats {
    std::size_t voxels_used = 0;    // voxels that wrote distances
    std::size_t voxels_left = 0;    // voxels without a usable normal, or too few points
    std::size_t grid_points = 0;    // grid points with a distance of enough weight
    std::size_t cells_dropped = 0;  // polygons left out: a corner of their cell had no value
    double fill_ms = 0.0;           // filling the grid
    double mesh_ms = 0.0;           // marching cubes and the mesh's arrays
};

// What the signed distance needs of a voxel: centre, unit normal (towards the sensor's side) and
// base weight (planarity_floor + planarity, times health when config.use_health), voxel frame.
struct SurfaceVoxel {
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();
    float weight = 0.0f;
};

// The voxels that take part: a unit normal, a finite centre, at least config.min_points points
// and a positive weight; the others are counted in *left_out.
std::vector<SurfaceVoxel> surface_voxels(const std::vector<common::VoxelData>& voxels,
                                         const MeshConfig& config, std::size_t* left_out = nullptr);

// The surface of `voxels` (one lattice of `voxel_size`), in the voxels' frame, outward faces
// (counter-clockwise seen from where the normals point: the sensor's side).
// Throws common::ConfigError (key under "mesh.") for a bad config or voxel size.
common::PlyMesh mesh_surface(const std::vector<SurfaceVoxel>& voxels, double voxel_size,
                             const MeshConfig& config, SdfStats* stats = nullptr);

// surface_voxels then mesh_surface.
common::PlyMesh mesh_voxels(const std::vector<common::VoxelData>& voxels, double voxel_size,
                            const MeshConfig& config, SdfStats* stats = nullptr);

}  // namespace ltm::mesh
