#include "simulator/core/world.hpp"

#include <algorithm>

#include "simulator/core/random.hpp"

namespace ltm::sim {

World::World(Mesh static_mesh) : static_mesh_(std::move(static_mesh)), bvh_(static_mesh_) {}

int World::add_prototype(Mesh mesh) {
    Prototype p;
    p.mesh = std::move(mesh);
    p.bvh = Bvh(p.mesh);
    for (const auto& v : p.mesh.vertices) p.radius = std::max(p.radius, v.head<2>().norm());
    prototypes_.push_back(std::move(p));
    return static_cast<int>(prototypes_.size()) - 1;
}

bool World::cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float max_range,
                 const ActorView* actors, int num_actors, std::uint64_t hash,
                 SurfaceHit& hit) const {
    constexpr int kMaxCrossings = 8;
    float t_from = 0.0f;
    for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
        float best = max_range;
        bool found = false;
        RayHit h;
        if (bvh_.intersect(origin, dir, t_from, best, h)) {
            best = h.t;
            found = true;
            hit.material = static_mesh_.material[h.triangle];
            hit.object = static_mesh_.object[h.triangle];
            hit.normal = bvh_.normal(h.triangle);
            hit.actor = false;
        }
        for (int a = 0; a < num_actors; ++a) {
            const ActorView& view = actors[a];
            const Prototype& p = prototypes_[static_cast<std::size_t>(view.prototype)];
            const Eigen::Vector3f o = view.T_actor_world * origin;
            const Eigen::Vector3f d = view.T_actor_world.linear() * dir;
            if (p.bvh.intersect(o, d, t_from, best, h)) {
                best = h.t;
                found = true;
                hit.material = p.mesh.material[h.triangle];
                hit.object = view.id;
                hit.normal = view.T_actor_world.linear().transpose() * p.bvh.normal(h.triangle);
                hit.actor = true;
            }
        }
        if (!found) return false;
        const float pass = material_properties(hit.material).pass;
        if (pass > 0.0f &&
            hash_unit(hash_mix(hash, 0x9A55, static_cast<std::uint64_t>(crossing))) < pass) {
            t_from = best + 1e-3f;
            continue;
        }
        hit.range = best;
        if (hit.normal.dot(dir) > 0.0f) hit.normal = -hit.normal;
        return true;
    }
    return false;
}

}  // namespace ltm::sim
