#pragma once
// The dense map as a set of chunks (one per local map), each in its anchor's frame, placed by the
// pose graph: after a loop closure, new anchor poses move the chunks and nothing is re-integrated.
//
// Overlapping local maps share space by ownership, not by averaging: a place belongs to the
// chunk with the nearest anchor among those that saw it (a surface voxel in the place's ownership
// cell, config.ownership_cell voxel sizes in that chunk's own lattice). Each chunk keeps the
// triangles whose centroid it owns; a triangle in a place no chunk saw (a surface's fringe) stays
// with its chunk. So where maps overlap there is one surface, not two slightly apart, and the
// seam follows the bisector between the anchors; where only one map saw a place, it keeps it.
//
// A chunk added without its mesh (prepare_chunk) is meshed in update(), over the cells it owns
// then and config.ownership_margin cells around them: local maps overlap a lot (a map takes the
// scans of 40 m of driving, 50 m around), and meshing each whole would mesh most places several
// times. When a chunk comes to own cells it has not meshed (anchors moved, a neighbour left), it
// is meshed again from its own voxels; nothing is re-integrated. When the graph moves chunks
// together (an optimisation spreads a correction along the route), ownership is worked out again
// only where neighbours moved relative to each other by more than config.ownership_tolerance.
//
// Chunks not (yet) in the graph (a local map folded into another by the long-term map, or one
// that arrived before its graph node) are placed by odometry: the correction of the graph chunk
// of the same odometry segment nearest in id before it (after it when none), or as the odometry
// put them when the segment has none.
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <memory>
#include <unordered_set>
#include <vector>

#include "common/core/ply_io.hpp"
#include "mesh/core/mesh_chunk.hpp"
#include "mesh/core/mesh_config.hpp"

namespace ltm::registration {
class ParallelFor;
}

namespace ltm::mesh {

struct AtlasTotals {
    std::size_t chunks = 0;
    std::size_t vertices = 0, triangles = 0;  // of every chunk's whole mesh
    std::size_t kept_triangles = 0;           // owned (what global_mesh holds)
    std::size_t meshings = 0;                 // chunks meshed by update() so far
    double fill_ms = 0.0, mesh_ms = 0.0;      // ... signed distance and marching cubes
};

class MeshAtlas {
  public:
    explicit MeshAtlas(const MeshConfig& config = {});
    ~MeshAtlas();
    MeshAtlas(MeshAtlas&&) noexcept;
    MeshAtlas& operator=(MeshAtlas&&) noexcept;

    // Adds a chunk or replaces the chunk of the same local map with a newer revision; an older or
    // equal revision is ignored (returns false).
    bool add(MeshChunk chunk);
    // Removes a chunk (returns false when there is none).
    bool remove(std::uint64_t local_map_id);
    // The graph's anchors, T_world_anchor by local map id (the whole set: anchors not named are no
    // longer in the graph).
    void set_graph(const std::map<std::uint64_t, Eigen::Isometry3d>& T_world_anchor);

    // Recomputes ownership where a chunk was added, replaced or moved (and in its neighbours),
    // meshes the chunks that own cells they have not meshed. Returns the ids of the chunks whose
    // kept triangles, mesh or pose changed since the last update.
    std::vector<std::uint64_t> update();

    bool has(std::uint64_t local_map_id) const { return entries_.count(local_map_id) > 0; }
    const MeshChunk* chunk(std::uint64_t local_map_id) const;
    std::vector<std::uint64_t> ids() const;
    // Where the chunk is (after update()): identity for an unknown id.
    Eigen::Isometry3d T_world_anchor(std::uint64_t local_map_id) const;
    bool in_graph(std::uint64_t local_map_id) const;
    // The triangles a chunk owns (after update()), anchor frame; empty for an unknown id.
    common::PlyMesh owned_mesh(std::uint64_t local_map_id) const;
    // Every chunk's owned triangles in the world frame (after update()).
    common::PlyMesh global_mesh() const;
    AtlasTotals totals() const;

  private:
    struct Entry {
        MeshChunk chunk;
        Eigen::Isometry3d T_world_anchor = Eigen::Isometry3d::Identity();
        Eigen::Isometry3d T_grid_world = Eigen::Isometry3d::Identity();
        Eigen::Vector3d centre_world = Eigen::Vector3d::Zero();
        std::vector<std::uint8_t> keep;  // per triangle of chunk.mesh
        bool dirty = true;               // new or replaced, or a neighbour was: ownership to redo
        bool fresh = true;               // new since the last update (neighbours only lose places)
        bool moved = false;              // pose changed since the last update
        bool reported = false;           // changed since the last update's report
        // The poses ownership was last worked out at: the chunk's and its neighbours' (by id).
        Eigen::Isometry3d T_owned = Eigen::Isometry3d::Identity();
        std::map<std::uint64_t, Eigen::Isometry3d> neighbours_owned;
        EIGEN_MAKE_ALIGNED_OPERATOR_NEW
    };

    void place();
    // Whether e's neighbours moved relative to it (or are new) by more than the tolerance since
    // its ownership was last worked out.
    bool moved_relative(const Entry& e, const std::vector<const Entry*>& neighbours) const;
    // The chunk's cells it owns (it has a voxel there and no nearer chunk does).
    std::vector<std::uint64_t> owned_cells(const Entry& e,
                                           const std::vector<const Entry*>& neighbours) const;
    // The owned cells and the margin around them when some are not meshed yet (else empty).
    std::unordered_set<std::uint64_t> cells_to_mesh(
        const Entry& e, const std::vector<const Entry*>& neighbours) const;
    // Which triangles the chunk keeps against `others`: from scratch (its neighbours), or, when
    // `others` are only new neighbours, what it kept less what they take.
    void own(Entry& e, const std::vector<const Entry*>& others, bool from_scratch);

    MeshConfig config_;
    std::map<std::uint64_t, Entry> entries_;
    std::map<std::uint64_t, Eigen::Isometry3d> graph_;
    std::unique_ptr<registration::ParallelFor> parallel_;
    std::size_t meshings_ = 0;
    double fill_ms_ = 0.0, mesh_ms_ = 0.0;
};

}  // namespace ltm::mesh
