#pragma once
// The mesh of one local map (a chunk of the dense map): its surface in the local map's anchor
// frame, so that when the pose graph moves the anchor the mesh moves with it and nothing is
// re-integrated; the cells of its lattice that hold its surface voxels (which places it saw), for
// sharing space with overlapping local maps (mesh_atlas); and those voxels, compact, so that the
// atlas can mesh only the places the chunk owns (and mesh more of them if it comes to own more).
#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_set>
#include <vector>

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
    double voxel_size = 1.0;                           // of the local map [m]
    double cell_size = 1.0;                            // ownership cell edge, grid frame [m]
    std::unordered_set<std::uint64_t> cells;           // ownership cells holding a surface voxel
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // bounding sphere, anchor frame [m]
    double radius = 0.0;
    std::vector<SurfaceVoxel> voxels;  // grid frame
    std::size_t voxels_left = 0;       // of the local map's voxels, not usable for the surface
    // The surface (anchor frame) of the voxels in `meshed_cells` (all of them when `complete`).
    common::PlyMesh mesh;
    bool complete = false;
    std::unordered_set<std::uint64_t> meshed_cells;
    SdfStats stats;  // of the last meshing

    // Whether the cell of p_grid (a point in the grid frame) holds a surface voxel.
    bool covers(const Eigen::Vector3d& p_grid) const;
    bool meshed(std::uint64_t cell) const { return complete || meshed_cells.count(cell) > 0; }
    // Whether the cell holds a surface voxel and is meshed.
    bool covers_meshed(std::uint64_t cell) const { return cells.count(cell) > 0 && meshed(cell); }
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// The chunk of a local map without its mesh: voxels, cells, bounding sphere. A MeshAtlas meshes
// it (the places it owns) in update().
// Throws common::ConfigError for a bad config or voxel size.
MeshChunk prepare_chunk(const common::LocalMapData& map, const MeshConfig& config);

// prepare_chunk, then the whole surface meshed (complete).
MeshChunk make_chunk(const common::LocalMapData& map, const MeshConfig& config);

// Meshes the chunk's voxels whose cell is in `cells` (anchor frame): its mesh, meshed_cells and
// stats are replaced; complete becomes false.
void mesh_cells(MeshChunk& chunk, const std::unordered_set<std::uint64_t>& cells,
                const MeshConfig& config);

// The ownership cell of a point (grid frame) and back (the cell's centre).
std::uint64_t cell_key(const Eigen::Vector3d& p, double cell_size);
Eigen::Vector3i cell_index(std::uint64_t key);
Eigen::Vector3d cell_centre(std::uint64_t key, double cell_size);
std::uint64_t cell_key(const Eigen::Vector3i& index);

}  // namespace ltm::mesh
