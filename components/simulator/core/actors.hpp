#pragma once
// Moving actors: vehicles and pedestrians going back and forth along their own paths, with the
// triangle models the ray caster intersects in each actor's own frame.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "simulator/core/bvh.hpp"
#include "simulator/core/geometry2d.hpp"
#include "simulator/core/mesh.hpp"
#include "simulator/core/scenario.hpp"
#include "simulator/core/terrain.hpp"

namespace ltm::sim {

class RobotPath;

class Actor {
  public:
    Actor(std::uint16_t id, const ActorConfig& config);

    std::uint16_t id() const { return id_; }
    ActorKind kind() const { return kind_; }
    const Points2& path() const { return path_.points(); }
    double half_width() const;            // [m] for its corridor
    Eigen::Vector2d half_extent() const;  // [m] plan footprint: half length, half width
    // Plan position and heading at session time t [s] (back and forth along the path).
    Eigen::Vector3d plan_pose_at(double t) const;  // x, y, yaw
    // T_world_actor at session time t, standing on the terrain.
    Eigen::Isometry3d pose_at(double t, const Terrain& terrain) const;

  private:
    std::uint16_t id_;
    ActorKind kind_;
    Polyline path_;
    double speed_, start_offset_;
};

// Procedural actors for one session: vehicles in the opposite lane of a stretch of the route,
// pedestrians beside it, each timed to pass the robot at least once and never to run into it
// (candidates that would are drawn again; after 30 tries the actor is left out). Deterministic
// by seed.
struct StreetProfile {
    double vehicle_offset = 2.7;  // [m] oncoming lane centre, left of the route
    double walk_min = 4.3;        // [m] pedestrians walk this far to either side ...
    double walk_max = 5.1;        // [m] ... up to this
};
// `left_out` (when given) receives how many procedural actors found no clear path.
std::vector<ActorConfig> make_session_actors(const ActorsConfig& config, const RobotPath& route,
                                             const StreetProfile& street, std::uint64_t seed,
                                             int* left_out = nullptr);

// The actor's triangles in its own frame (x forward, z up from the ground). Object id = actor id.
Mesh actor_mesh(ActorKind kind, std::uint16_t id, std::uint64_t seed);

}  // namespace ltm::sim
