#pragma once
// The mesh of one local map (a chunk of the dense map): its surface in the local map's anchor
// frame, so that when the pose graph moves the anchor the mesh moves with it and nothing is
// re-integrated, and the cells of its lattice that hold its voxels (which places it saw), for
// sharing space with overlapping local maps (mesh_atlas).
#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_set>

#include "common/core/local_map_data.hpp"
#include "common/core/ply_io.hpp"
#include "mesh/core/mesh_config.hpp"
#include "mesh/core/sdf_mesher.hpp"

namespace ltm::mesh {

struct MeshChunk {
    std::uint64_t local_map_id = 0;
    std::uint32_t revision = 0;
    std::uint32_t segment = 0;
    Eigen::Isometry3d T_odom_anchor = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_anchor_grid = Eigen::Isometry3d::Identity();
    double cell_size = 1.0;                            // ownership cell edge, grid frame [m]
    std::unordered_set<std::uint64_t> cells;           // ownership cells holding a surface voxel
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // bounding sphere, anchor frame [m]
    double radius = 0.0;
    common::PlyMesh mesh;  // anchor frame
    SdfStats stats;

    // Whether the cell of p_grid (a point in the grid frame) holds a surface voxel.
    bool covers(const Eigen::Vector3d& p_grid) const;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// The chunk of a local map: mesh_voxels on its voxels, moved to the anchor frame.
// Throws common::ConfigError for a bad config or voxel size.
MeshChunk make_chunk(const common::LocalMapData& map, const MeshConfig& config);

std::uint64_t cell_key(const Eigen::Vector3d& p, double cell_size);

}  // namespace ltm::mesh
