#include "mesh/core/mesh_atlas.hpp"

#include <utility>

#include "mesh/core/triangle_mesh.hpp"

namespace ltm::mesh {

namespace {

bool same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff() < 1e-9;
}

}  // namespace

MeshAtlas::MeshAtlas(const MeshConfig& config) : config_(config) {
    common::throw_if(validate(config), "mesh");
}

bool MeshAtlas::add(MeshChunk chunk) {
    const std::uint64_t id = chunk.local_map_id;
    auto it = entries_.find(id);
    if (it != entries_.end() && chunk.revision <= it->second.chunk.revision) return false;
    Entry& e = entries_[id];
    // The neighbours of the old extent must give back what it no longer covers.
    if (it != entries_.end())
        for (auto& [oid, o] : entries_)
            if (oid != id &&
                (o.centre_world - e.centre_world).norm() < o.chunk.radius + e.chunk.radius)
                o.dirty = true;
    e.chunk = std::move(chunk);
    e.keep.assign(e.chunk.mesh.triangles.size(), 1);
    e.dirty = true;
    return true;
}

bool MeshAtlas::remove(std::uint64_t local_map_id) {
    auto it = entries_.find(local_map_id);
    if (it == entries_.end()) return false;
    for (auto& [oid, o] : entries_)
        if (oid != local_map_id && (o.centre_world - it->second.centre_world).norm() <
                                       o.chunk.radius + it->second.chunk.radius)
            o.dirty = true;
    entries_.erase(it);
    return true;
}

void MeshAtlas::set_graph(const std::map<std::uint64_t, Eigen::Isometry3d>& T_world_anchor) {
    graph_ = T_world_anchor;
}

void MeshAtlas::place() {
    for (auto& [id, e] : entries_) {
        Eigen::Isometry3d T = e.chunk.T_odom_anchor;
        const auto g = graph_.find(id);
        if (g != graph_.end()) {
            T = g->second;
        } else {
            // The odometry correction of the nearest graph chunk of the same segment.
            const Entry* ref = nullptr;
            std::uint64_t ref_id = 0;
            for (const auto& [oid, o] : entries_) {
                if (o.chunk.segment != e.chunk.segment || !graph_.count(oid)) continue;
                const bool before = oid < id, ref_before = ref && ref_id < id;
                if (!ref || (before && (!ref_before || oid > ref_id)) ||
                    (!before && !ref_before && oid < ref_id)) {
                    ref = &o;
                    ref_id = oid;
                }
            }
            if (ref)
                T = graph_.at(ref_id) * ref->chunk.T_odom_anchor.inverse() * e.chunk.T_odom_anchor;
        }
        if (!same_pose(T, e.T_world_anchor) || e.dirty) {
            e.T_world_anchor = T;
            e.T_grid_world = (T * e.chunk.T_anchor_grid).inverse();
            e.centre_world = T * e.chunk.centre;
            e.dirty = true;
        }
    }
}

void MeshAtlas::own(Entry& e, const std::vector<const Entry*>& neighbours) {
    const common::PlyMesh& mesh = e.chunk.mesh;
    std::vector<std::uint8_t> keep(mesh.triangles.size(), 1);
    if (!neighbours.empty()) {
        const Eigen::Vector3d a = e.T_world_anchor.translation();
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            const Eigen::Vector3d x = e.T_world_anchor * centroid(mesh, t).cast<double>();
            const bool mine = e.chunk.covers(e.T_grid_world * x);
            const double d_mine = (x - a).squaredNorm();
            for (const Entry* o : neighbours) {
                if ((x - o->centre_world).squaredNorm() > o->chunk.radius * o->chunk.radius)
                    continue;
                const double d = (x - o->T_world_anchor.translation()).squaredNorm();
                const bool nearer =
                    d < d_mine || (d == d_mine && o->chunk.local_map_id < e.chunk.local_map_id);
                if ((!mine || nearer) && o->chunk.covers(o->T_grid_world * x)) {
                    keep[t] = 0;
                    break;
                }
            }
        }
    }
    if (keep != e.keep) e.reported = true;
    e.keep = std::move(keep);
}

std::vector<std::uint64_t> MeshAtlas::update() {
    place();
    std::vector<Entry*> affected;
    for (auto& [id, e] : entries_) {
        bool touched = e.dirty;
        if (!touched)
            for (const auto& [oid, o] : entries_)
                if (o.dirty &&
                    (o.centre_world - e.centre_world).norm() < o.chunk.radius + e.chunk.radius) {
                    touched = true;
                    break;
                }
        if (touched) affected.push_back(&e);
    }
    for (Entry* e : affected) {
        std::vector<const Entry*> neighbours;
        for (const auto& [oid, o] : entries_)
            if (&o != e &&
                (o.centre_world - e->centre_world).norm() < o.chunk.radius + e->chunk.radius)
                neighbours.push_back(&o);
        if (e->dirty) e->reported = true;
        own(*e, neighbours);
    }
    std::vector<std::uint64_t> changed;
    for (auto& [id, e] : entries_) {
        if (e.reported) changed.push_back(id);
        e.reported = false;
        e.dirty = false;
    }
    return changed;
}

const MeshChunk* MeshAtlas::chunk(std::uint64_t local_map_id) const {
    const auto it = entries_.find(local_map_id);
    return it == entries_.end() ? nullptr : &it->second.chunk;
}

std::vector<std::uint64_t> MeshAtlas::ids() const {
    std::vector<std::uint64_t> out;
    for (const auto& [id, e] : entries_) out.push_back(id);
    return out;
}

Eigen::Isometry3d MeshAtlas::T_world_anchor(std::uint64_t local_map_id) const {
    const auto it = entries_.find(local_map_id);
    return it == entries_.end() ? Eigen::Isometry3d::Identity() : it->second.T_world_anchor;
}

bool MeshAtlas::in_graph(std::uint64_t local_map_id) const {
    return graph_.count(local_map_id) > 0;
}

common::PlyMesh MeshAtlas::owned_mesh(std::uint64_t local_map_id) const {
    const auto it = entries_.find(local_map_id);
    if (it == entries_.end()) return {};
    return sub_mesh(it->second.chunk.mesh, it->second.keep);
}

common::PlyMesh MeshAtlas::global_mesh() const {
    common::PlyMesh out;
    for (const auto& [id, e] : entries_)
        append(out, sub_mesh(e.chunk.mesh, e.keep), e.T_world_anchor);
    return out;
}

AtlasTotals MeshAtlas::totals() const {
    AtlasTotals t;
    for (const auto& [id, e] : entries_) {
        ++t.chunks;
        t.vertices += e.chunk.mesh.vertices.size();
        t.triangles += e.chunk.mesh.triangles.size();
        for (const std::uint8_t k : e.keep) t.kept_triangles += k;
    }
    return t;
}

}  // namespace ltm::mesh
