#include "mesh/component/mesh_messages.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/convert/pose_graph.hpp"

namespace ltm::mesh {
namespace {

bool finite(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

// x y z triples of a float sequence; throws naming `what`.
template <class View>
std::vector<Eigen::Vector3f> triples(const View& v, const std::string& chunk, const char* what) {
    if (v.size() % 3 != 0)
        throw std::invalid_argument(chunk + ": " + std::to_string(v.size()) + " " + what +
                                    " coordinates, not x y z triples");
    std::vector<Eigen::Vector3f> out(v.size() / 3);
    for (std::uint32_t k = 0; k < out.size(); ++k) {
        out[k] = {v[3 * k], v[3 * k + 1], v[3 * k + 2]};
        if (!out[k].allFinite())
            throw std::invalid_argument(chunk + ": " + what + " " + std::to_string(k) +
                                        " is not finite");
    }
    return out;
}

}  // namespace

PlacedMesh placed_chunk(const MeshAtlas& atlas, std::uint64_t id) {
    PlacedMesh p;
    p.local_map_id = id;
    if (const MeshChunk* c = atlas.chunk(id)) p.revision = c->revision;
    p.T_map_anchor = atlas.T_world_anchor(id);
    p.mesh = atlas.owned_mesh(id);
    return p;
}

convert::Owned<msg::Mesh> to_msg(const PlacedMesh& c, const msg::Time& stamp,
                                 const std::string& frame_id) {
    convert::Owned<msg::Mesh> m;
    m->header.stamp = stamp;
    convert::set_string(m->header.frame_id, frame_id);
    m->local_map_id = c.local_map_id;
    m->revision = c.revision;
    m->anchor = convert::to_pose(c.T_map_anchor);
    const auto copy = [](auto& seq, const std::vector<Eigen::Vector3f>& v) {
        float* out = convert::alloc_sequence(seq, 3 * v.size());
        for (const Eigen::Vector3f& p : v) {
            std::memcpy(out, p.data(), 3 * sizeof(float));
            out += 3;
        }
    };
    copy(m->vertices, c.mesh.vertices);
    copy(m->normals, c.mesh.normals);
    std::uint32_t* t = convert::alloc_sequence(m->triangles, 3 * c.mesh.triangles.size());
    for (const Eigen::Vector3i& tri : c.mesh.triangles)
        for (int k = 0; k < 3; ++k) *t++ = static_cast<std::uint32_t>(tri[k]);
    return m;
}

PlacedMesh from_msg(const msg::Mesh& m) {
    const std::string chunk = "mesh chunk " + std::to_string(m.local_map_id);
    PlacedMesh p;
    p.local_map_id = m.local_map_id;
    p.revision = m.revision;
    p.T_map_anchor = convert::to_isometry(m.anchor);
    if (!finite(p.T_map_anchor)) throw std::invalid_argument(chunk + ": anchor pose not finite");
    p.mesh.vertices = triples(convert::view(m.vertices), chunk, "vertex");
    p.mesh.normals = triples(convert::view(m.normals), chunk, "normal");
    if (!p.mesh.normals.empty() && p.mesh.normals.size() != p.mesh.vertices.size())
        throw std::invalid_argument(chunk + ": " + std::to_string(p.mesh.normals.size()) +
                                    " normals for " + std::to_string(p.mesh.vertices.size()) +
                                    " vertices");
    const auto t = convert::view(m.triangles);
    if (t.size() % 3 != 0)
        throw std::invalid_argument(chunk + ": " + std::to_string(t.size()) +
                                    " triangle indices, not triples");
    p.mesh.triangles.resize(t.size() / 3);
    const std::size_t n = p.mesh.vertices.size();
    for (std::uint32_t k = 0; k < p.mesh.triangles.size(); ++k) {
        for (int i = 0; i < 3; ++i) {
            const std::uint32_t v = t[3 * k + i];
            if (v >= n)
                throw std::invalid_argument(chunk + ": triangle " + std::to_string(k) +
                                            " names vertex " + std::to_string(v) + " of " +
                                            std::to_string(n));
            p.mesh.triangles[k][i] = static_cast<int>(v);
        }
    }
    return p;
}

common::LocalMapData local_map_from_msg(const msg::LocalMap& m) {
    common::LocalMapData d = convert::from_msg(m);
    const std::string map = "local map " + std::to_string(d.id);
    if (!finite(d.T_odom_anchor)) throw std::invalid_argument(map + ": anchor pose not finite");
    if (!finite(d.T_anchor_grid)) throw std::invalid_argument(map + ": grid pose not finite");
    if (!(d.voxel_size > 0.0f) || !std::isfinite(d.voxel_size))
        throw std::invalid_argument(map + ": voxel size " + std::to_string(d.voxel_size) +
                                    " is not a positive number");
    return d;
}

std::map<std::uint64_t, Eigen::Isometry3d> anchors_from_msg(const msg::PoseGraph& m) {
    const convert::PoseGraphData g = convert::from_msg(m);
    const std::string graph = "pose graph revision " + std::to_string(g.revision);
    std::map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const convert::GraphAnchor& a : g.anchors) {
        const std::string anchor =
            graph + ": anchor of local map " + std::to_string(a.local_map_id);
        if (!finite(a.T_map_anchor)) throw std::invalid_argument(anchor + ": pose not finite");
        if (!anchors.emplace(a.local_map_id, a.T_map_anchor).second)
            throw std::invalid_argument(anchor + ": given twice");
    }
    return anchors;
}

}  // namespace ltm::mesh
