#pragma once
// The mesh component's messages: a chunk of the dense map (the triangles one local map owns, in
// its anchor frame, with where the pose graph puts that anchor) <-> ltm_msgs/Mesh, and the checks
// that keep a bad LocalMap or PoseGraph message away from the mesh core (the conversions
// themselves are runtime/convert's).
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <string>

#include "common/core/local_map_data.hpp"
#include "common/core/ply_io.hpp"
#include "mesh/core/mesh_atlas.hpp"
#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::mesh {

// A chunk as it travels: ltm_msgs/Mesh's content.
struct PlacedMesh {
    std::uint64_t local_map_id = 0;
    std::uint32_t revision = 0;
    Eigen::Isometry3d T_map_anchor = Eigen::Isometry3d::Identity();
    common::PlyMesh mesh;  // anchor frame; normals empty or one per vertex
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// Chunk `id` of an atlas as it stands after update(): its owned triangles, its anchor's pose.
PlacedMesh placed_chunk(const MeshAtlas& atlas, std::uint64_t id);

convert::Owned<msg::Mesh> to_msg(const PlacedMesh& chunk, const msg::Time& stamp,
                                 const std::string& frame_id);

// The chunk of a message (any sample: it is checked). Throws std::invalid_argument, one line
// naming the chunk, for coordinates that are not x y z triples, normals not one per vertex,
// triangles not index triples or naming a vertex that is not there, a non-finite coordinate or
// anchor pose.
PlacedMesh from_msg(const msg::Mesh& m);

// A LocalMap message as the core's data (convert::from_msg), checked: throws
// std::invalid_argument, one line naming the map, for a non-finite anchor or grid pose or a voxel
// size that is not a positive number. Voxels with a non-finite centre or normal pass: the mesher
// leaves them out.
common::LocalMapData local_map_from_msg(const msg::LocalMap& m);

// The pose graph's anchors, T_map_anchor by local map id (convert::from_msg), checked: throws
// std::invalid_argument, one line naming the graph's revision, for a non-finite pose or an anchor
// named twice.
std::map<std::uint64_t, Eigen::Isometry3d> anchors_from_msg(const msg::PoseGraph& m);

}  // namespace ltm::mesh
