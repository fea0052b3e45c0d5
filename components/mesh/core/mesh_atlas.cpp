#include "mesh/core/mesh_atlas.hpp"

#include <algorithm>
#include <thread>
#include <utility>

#include "mesh/core/triangle_mesh.hpp"
#include "registration/core/parallel.hpp"

namespace ltm::mesh {

namespace {

bool same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff() < 1e-9;
}

}  // namespace

MeshAtlas::MeshAtlas(const MeshConfig& config) : config_(config) {
    common::throw_if(validate(config), "mesh");
    const int threads = config.threads > 0 ? config.threads
                                           : int(std::max(1u, std::thread::hardware_concurrency()));
    parallel_ = std::make_unique<registration::ParallelFor>(threads);
}

MeshAtlas::~MeshAtlas() = default;
MeshAtlas::MeshAtlas(MeshAtlas&&) noexcept = default;
MeshAtlas& MeshAtlas::operator=(MeshAtlas&&) noexcept = default;

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
    e.fresh = it == entries_.end();
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
            e.moved = e.moved || !same_pose(T, e.T_world_anchor);
            e.T_world_anchor = T;
            e.T_grid_world = (T * e.chunk.T_anchor_grid).inverse();
            e.centre_world = T * e.chunk.centre;
        }
    }
}

bool MeshAtlas::moved_relative(const Entry& e, const std::vector<const Entry*>& neighbours) const {
    if (neighbours.size() != e.neighbours_owned.size()) return true;
    for (const Entry* o : neighbours) {
        const auto it = e.neighbours_owned.find(o->chunk.local_map_id);
        if (it == e.neighbours_owned.end()) return true;
        const Eigen::Isometry3d then = e.T_owned.inverse() * it->second;
        const Eigen::Isometry3d now = e.T_world_anchor.inverse() * o->T_world_anchor;
        const Eigen::Isometry3d d = then.inverse() * now;
        const double angle = Eigen::AngleAxisd(d.linear()).angle();
        if (d.translation().norm() + angle * e.chunk.radius > config_.ownership_tolerance)
            return true;
    }
    return false;
}

std::vector<std::uint64_t> MeshAtlas::owned_cells(
    const Entry& e, const std::vector<const Entry*>& neighbours) const {
    std::vector<std::uint64_t> owned;
    owned.reserve(e.chunk.cells.size());
    const Eigen::Isometry3d T_world_grid = e.T_world_anchor * e.chunk.T_anchor_grid;
    const Eigen::Vector3d a = e.T_world_anchor.translation();
    for (const std::uint64_t key : e.chunk.cells) {
        const Eigen::Vector3d x = T_world_grid * cell_centre(key, e.chunk.cell_size);
        const double d_mine = (x - a).squaredNorm();
        bool mine = true;
        for (const Entry* o : neighbours) {
            if ((x - o->centre_world).squaredNorm() > o->chunk.radius * o->chunk.radius) continue;
            const double d = (x - o->T_world_anchor.translation()).squaredNorm();
            const bool nearer =
                d < d_mine || (d == d_mine && o->chunk.local_map_id < e.chunk.local_map_id);
            if (nearer && o->chunk.covers(o->T_grid_world * x)) {
                mine = false;
                break;
            }
        }
        if (mine) owned.push_back(key);
    }
    return owned;
}

std::unordered_set<std::uint64_t> MeshAtlas::cells_to_mesh(
    const Entry& e, const std::vector<const Entry*>& neighbours) const {
    std::unordered_set<std::uint64_t> cells;
    if (e.chunk.complete) return cells;
    const std::vector<std::uint64_t> owned = owned_cells(e, neighbours);
    // Meshed again when too much of what it owns is not meshed (the others keep their surface
    // there meanwhile, see own()).
    std::size_t missing = 0;
    for (const std::uint64_t key : owned) missing += e.chunk.meshed(key) ? 0 : 1;
    const bool never = e.chunk.meshed_cells.empty() && !owned.empty();
    if (!never &&
        (missing == 0 || double(missing) <= config_.remesh_fraction * double(owned.size())))
        return cells;
    // The owned cells and the chunk's cells within the margin of them.
    cells.insert(owned.begin(), owned.end());
    const int m = config_.ownership_margin;
    for (const std::uint64_t key : owned) {
        const Eigen::Vector3i c = cell_index(key);
        for (int dz = -m; dz <= m; ++dz)
            for (int dy = -m; dy <= m; ++dy)
                for (int dx = -m; dx <= m; ++dx) {
                    const std::uint64_t k =
                        cell_key(Eigen::Vector3i(c + Eigen::Vector3i(dx, dy, dz)));
                    if (e.chunk.cells.count(k)) cells.insert(k);
                }
    }
    return cells;
}

void MeshAtlas::own(Entry& e, const std::vector<const Entry*>& neighbours, bool from_scratch) {
    const common::PlyMesh& mesh = e.chunk.mesh;
    std::vector<std::uint8_t> keep =
        from_scratch ? std::vector<std::uint8_t>(mesh.triangles.size(), 1) : e.keep;
    if (!neighbours.empty()) {
        const Eigen::Vector3d a = e.T_world_anchor.translation();
        // Consecutive triangles mostly share their cells (marching cubes goes leaf by leaf): the
        // last cell's answer of each chunk is kept.
        struct Memo {
            std::uint64_t key = ~std::uint64_t(0);
            bool value = false;
        };
        auto cached = [](Memo& m, std::uint64_t key, auto&& compute) {
            if (m.key != key) {
                m.key = key;
                m.value = compute(key);
            }
            return m.value;
        };
        Memo mine_memo;
        std::vector<Memo> memo(neighbours.size());
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            if (!keep[t]) continue;  // given up already (from scratch: none is)
            const Eigen::Vector3d x = e.T_world_anchor * centroid(mesh, t).cast<double>();
            const bool mine = cached(mine_memo, cell_key(e.T_grid_world * x, e.chunk.cell_size),
                                     [&](std::uint64_t k) { return e.chunk.cells.count(k) > 0; });
            const double d_mine = (x - a).squaredNorm();
            for (std::size_t j = 0; j < neighbours.size(); ++j) {
                const Entry* o = neighbours[j];
                if ((x - o->centre_world).squaredNorm() > o->chunk.radius * o->chunk.radius)
                    continue;
                const double d = (x - o->T_world_anchor.translation()).squaredNorm();
                const bool nearer =
                    d < d_mine || (d == d_mine && o->chunk.local_map_id < e.chunk.local_map_id);
                if (mine && !nearer) continue;
                // Given up to the other chunk when it saw the place and has meshed it (until it
                // does, this chunk's surface stays: no hole while ownership moves).
                const bool theirs =
                    cached(memo[j], cell_key(o->T_grid_world * x, o->chunk.cell_size),
                           [&](std::uint64_t k) { return o->chunk.covers_meshed(k); });
                if (theirs) {
                    keep[t] = 0;
                    break;
                }
            }
        }
    }
    if (keep != e.keep) e.reported = true;
    e.keep = std::move(keep);
    if (from_scratch) {
        e.T_owned = e.T_world_anchor;
        e.neighbours_owned.clear();
    }
    for (const Entry* o : neighbours) e.neighbours_owned[o->chunk.local_map_id] = o->T_world_anchor;
}

std::vector<std::uint64_t> MeshAtlas::update() {
    place();
    // Ownership is worked out again for new or replaced chunks, the neighbours of replaced ones,
    // and chunks whose neighbours moved relative to them; a chunk with only new neighbours gives
    // them what they take (a new chunk can only take places, never give any).
    std::vector<Entry*> affected;
    std::vector<std::vector<const Entry*>> neighbours;
    std::vector<std::uint8_t> from_scratch;
    for (auto& [id, e] : entries_) {
        std::vector<const Entry*> near, fresh;
        bool full = e.dirty;
        for (const auto& [oid, o] : entries_) {
            if (&o == &e ||
                (o.centre_world - e.centre_world).norm() >= o.chunk.radius + e.chunk.radius)
                continue;
            if (o.fresh)
                fresh.push_back(&o);
            else
                near.push_back(&o);
            full = full || (o.dirty && !o.fresh);
        }
        if (!full && (e.moved || std::any_of(near.begin(), near.end(),
                                             [](const Entry* o) { return o->moved; })))
            full = moved_relative(e, near);
        if (e.moved) e.reported = true;  // its pose changed: worth publishing
        if (full) {
            near.insert(near.end(), fresh.begin(), fresh.end());
            affected.push_back(&e);
            neighbours.push_back(std::move(near));
            from_scratch.push_back(1);
        } else if (!fresh.empty()) {
            affected.push_back(&e);
            neighbours.push_back(std::move(fresh));
            from_scratch.push_back(0);
        }
    }
    // Each affected chunk's neighbours, the cells it must mesh (none: its mesh covers what it
    // owns), then meshing and ownership, a chunk a task (each task writes its own chunk only).
    const std::size_t n = affected.size();
    for (std::size_t i = 0; i < n; ++i)
        if (affected[i]->dirty) affected[i]->reported = true;
    std::vector<std::unordered_set<std::uint64_t>> cells(n);
    parallel_->run(n, 1, [&](std::size_t, std::size_t b, std::size_t end) {
        for (std::size_t i = b; i < end; ++i) {
            if (!from_scratch[i]) continue;  // new neighbours only take places away
            cells[i] = cells_to_mesh(*affected[i], neighbours[i]);
            if (cells[i].empty()) continue;
            Entry& e = *affected[i];
            mesh_cells(e.chunk, cells[i], config_);
            e.keep.assign(e.chunk.mesh.triangles.size(), 1);
            e.reported = true;
        }
    });
    for (std::size_t i = 0; i < n; ++i)
        if (!cells[i].empty()) {
            ++meshings_;
            fill_ms_ += affected[i]->chunk.stats.fill_ms;
            mesh_ms_ += affected[i]->chunk.stats.mesh_ms;
        }
    parallel_->run(n, 1, [&](std::size_t, std::size_t b, std::size_t end) {
        for (std::size_t i = b; i < end; ++i)
            own(*affected[i], neighbours[i], from_scratch[i] || !cells[i].empty());
    });
    std::vector<std::uint64_t> changed;
    for (auto& [id, e] : entries_) {
        if (e.reported) changed.push_back(id);
        e.reported = false;
        e.dirty = false;
        e.fresh = false;
        e.moved = false;
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
    std::size_t vertices = 0, triangles = 0;
    bool normals = true;
    for (const auto& [id, e] : entries_) {
        vertices += e.chunk.mesh.vertices.size();
        for (const std::uint8_t k : e.keep) triangles += k;
        normals = normals && e.chunk.mesh.normals.size() == e.chunk.mesh.vertices.size();
    }
    out.vertices.reserve(vertices);
    out.triangles.reserve(triangles);
    if (normals) out.normals.reserve(vertices);
    std::vector<int> remap;
    for (const auto& [id, e] : entries_) {
        const common::PlyMesh& m = e.chunk.mesh;
        const Eigen::Isometry3f T = e.T_world_anchor.cast<float>();
        const Eigen::Matrix3f R = T.linear();
        remap.assign(m.vertices.size(), -1);
        for (std::size_t t = 0; t < m.triangles.size() && t < e.keep.size(); ++t) {
            if (!e.keep[t]) continue;
            Eigen::Vector3i u;
            for (int k = 0; k < 3; ++k) {
                int& r = remap[m.triangles[t][k]];
                if (r < 0) {
                    r = int(out.vertices.size());
                    out.vertices.push_back(T * m.vertices[m.triangles[t][k]]);
                    if (normals) out.normals.push_back(R * m.normals[m.triangles[t][k]]);
                }
                u[k] = r;
            }
            out.triangles.push_back(u);
        }
    }
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
    t.meshings = meshings_;
    t.fill_ms = fill_ms_;
    t.mesh_ms = mesh_ms_;
    return t;
}

}  // namespace ltm::mesh
