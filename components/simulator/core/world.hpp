#pragma once
// The scene a pulse can hit: the static surfaces in one BVH and the moving actors, each a small
// BVH in its own frame, intersected through the actor's pose at the pulse time.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "simulator/core/bvh.hpp"
#include "simulator/core/materials.hpp"
#include "simulator/core/mesh.hpp"

namespace ltm::sim {

struct SurfaceHit {
    float range = 0.0f;                                 // [m] along the unit direction
    Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  // unit, facing the ray
    Material material = Material::kConcrete;
    std::uint32_t object = 0;  // static object id (0 terrain) or actor id
    bool actor = false;
};

// An actor model placed for one pulse: its prototype and the inverse of its pose.
struct ActorView {
    int prototype = 0;
    std::uint16_t id = 0;
    Eigen::Isometry3f T_actor_world = Eigen::Isometry3f::Identity();
};

class World {
  public:
    World() = default;
    explicit World(Mesh static_mesh);

    // Adds an actor model (in its own frame); returns its prototype index.
    int add_prototype(Mesh mesh);
    const Mesh& static_mesh() const { return static_mesh_; }
    const Mesh& prototype_mesh(int i) const {
        return prototypes_[static_cast<std::size_t>(i)].mesh;
    }
    // Radius of the prototype's plan-view bounding circle about its origin [m].
    float prototype_radius(int i) const { return prototypes_[static_cast<std::size_t>(i)].radius; }

    // The surface a pulse from `origin` along unit `dir` returns from, within max_range.
    // Porous surfaces (foliage, fences, glass) let it through with their pass probability,
    // decided by `hash` so the result is deterministic.
    bool cast(const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float max_range,
              const ActorView* actors, int num_actors, std::uint64_t hash, SurfaceHit& hit) const;

  private:
    struct Prototype {
        Mesh mesh;
        Bvh bvh;
        float radius = 0.0f;
    };
    Mesh static_mesh_;
    Bvh bvh_;
    std::vector<Prototype> prototypes_;
};

}  // namespace ltm::sim
