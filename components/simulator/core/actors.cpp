#include "simulator/core/actors.hpp"

#include <algorithm>
#include <cmath>

#include "simulator/core/random.hpp"
#include "simulator/core/robot_path.hpp"

namespace ltm::sim {
namespace {

// A stretch [s0, s1] of a polyline as its own point list.
Points2 stretch(const Polyline& line, double s0, double s1, double step) {
    Points2 out;
    s0 = std::clamp(s0, 0.0, line.length());
    s1 = std::clamp(s1, 0.0, line.length());
    const int n = std::max(1, static_cast<int>(std::ceil((s1 - s0) / step)));
    for (int k = 0; k <= n; ++k) out.push_back(line.point_at(s0 + (s1 - s0) * k / n));
    return out;
}

}  // namespace

Actor::Actor(std::uint16_t id, const ActorConfig& config)
    : id_(id),
      kind_(config.kind),
      path_(config.waypoints),
      speed_(config.speed),
      start_offset_(config.start_offset) {}

double Actor::half_width() const { return kind_ == ActorKind::kPedestrian ? 0.4 : 0.95; }

Eigen::Vector2d Actor::half_extent() const {
    switch (kind_) {
        case ActorKind::kCar:
            return {2.3, 0.95};
        case ActorKind::kVan:
            return {2.75, 1.05};
        case ActorKind::kPedestrian:
            break;
    }
    return {0.35, 0.35};
}

Eigen::Vector3d Actor::plan_pose_at(double t) const {
    const double L = path_.length();
    if (L <= 0) {
        const Eigen::Vector2d p = path_.point_at(0);
        return {p.x(), p.y(), 0.0};
    }
    double u = std::fmod(start_offset_ + speed_ * t, 2 * L);
    if (u < 0) u += 2 * L;
    const bool back = u > L;
    const double s = back ? 2 * L - u : u;
    const Eigen::Vector2d p = path_.point_at(s);
    Eigen::Vector2d d = path_.point_at(s + 0.5) - path_.point_at(s - 0.5);
    if (d.norm() < 1e-9) d = path_.tangent_at(s);
    if (back) d = -d;
    return {p.x(), p.y(), std::atan2(d.y(), d.x())};
}

Eigen::Isometry3d Actor::pose_at(double t, const Terrain& terrain) const {
    const Eigen::Vector3d p = plan_pose_at(t);
    Eigen::Isometry3d T = ground_pose(p.x(), p.y(), terrain.height(p.x(), p.y()), p.z());
    if (kind_ != ActorKind::kPedestrian) {
        const Eigen::Vector3d n = terrain.normal(p.x(), p.y());
        T.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n) * T.linear();
    }
    return T;
}

std::vector<ActorConfig> make_session_actors(const ActorsConfig& config, const RobotPath& route,
                                             const StreetProfile& street, std::uint64_t seed,
                                             int* left_out) {
    std::vector<ActorConfig> out = config.placed;
    if (left_out) *left_out = 0;
    Rng rng(hash_mix(seed, 0xAC7025));
    const Polyline& line = route.centerline();
    const double duration = std::max(route.duration(), 1.0);
    // Robot positions every half second: an actor whose path would run into the robot (a later
    // pass of the route using the oncoming lane, say) is drawn again.
    // The robot's footprint is taken as a car's (4.8 m x 2 m).
    std::vector<OrientedRect> robot;
    for (double t = 0; t <= duration; t += 0.5) {
        const Eigen::Vector2d d = route.plan_position(t + 0.25) - route.plan_position(t - 0.25);
        robot.push_back(
            {route.plan_position(t), {2.4, 1.0}, d.norm() > 1e-6 ? std::atan2(d.y(), d.x()) : 0.0});
    }
    for (int k = 0; k < config.vehicles + config.pedestrians; ++k) {
        const bool vehicle = k < config.vehicles;
        for (int attempt = 0; attempt < 30; ++attempt) {
            ActorConfig a;
            a.kind = vehicle ? (rng.chance(0.75) ? ActorKind::kCar : ActorKind::kVan)
                             : ActorKind::kPedestrian;
            a.speed = vehicle ? rng.uniform(4.0, 8.0) : rng.uniform(1.1, 1.6);
            // Meet the robot at a random time, on a stretch of its route centred there.
            const double t_meet = rng.uniform(0.05, 0.95) * duration;
            const double s_meet = route.arc_at(t_meet);
            const double half_len = vehicle ? rng.uniform(50.0, 120.0) : rng.uniform(12.0, 30.0);
            const Points2 base =
                stretch(line, s_meet - half_len, s_meet + half_len, vehicle ? 2.0 : 1.0);
            const double side = rng.chance(0.5) ? 1.0 : -1.0;
            const double lateral = vehicle ? street.vehicle_offset
                                           : side * rng.uniform(street.walk_min, street.walk_max);
            a.waypoints = offset_polyline(base, lateral);
            if (vehicle) std::reverse(a.waypoints.begin(), a.waypoints.end());  // oncoming traffic
            const Polyline path(a.waypoints);
            // Where the robot is at t_meet along this path, and back-and-forth phase to be there.
            const double s_here = path.project(route.plan_position(t_meet));
            a.start_offset = std::fmod(s_here - a.speed * t_meet, 2 * path.length());
            if (a.start_offset < 0) a.start_offset += 2 * path.length();
            const Actor probe(0, a);
            bool clear = true;
            for (std::size_t i = 0; clear && i < robot.size(); ++i) {
                const Eigen::Vector3d p = probe.plan_pose_at(0.5 * static_cast<double>(i));
                clear = !rects_overlap(robot[i], {p.head<2>(), probe.half_extent(), p.z()}, 0.25);
            }
            if (clear) {
                out.push_back(a);
                break;
            }
            if (attempt == 29 && left_out) ++*left_out;
        }
    }
    return out;
}

Mesh actor_mesh(ActorKind kind, std::uint16_t id, std::uint64_t seed) {
    Mesh mesh;
    if (kind == ActorKind::kPedestrian) {
        MeshBuilder b(mesh);
        b.set_object(id);
        Rng rng(hash_mix(seed, id));
        const double h = rng.uniform(1.6, 1.9);
        const double stride = rng.uniform(0.15, 0.3);  // legs apart, mid-step
        b.set_material(Material::kFabric);
        b.frustum({-stride, -0.1, 0.0}, {0.0, -0.1, 0.48 * h}, 0.07, 0.09, 8);
        b.frustum({stride, 0.1, 0.0}, {0.0, 0.1, 0.48 * h}, 0.07, 0.09, 8);
        b.ellipsoid({0.0, 0.0, 0.66 * h}, {0.13, 0.22, 0.2 * h});
        b.frustum({0.05, -0.26, 0.8 * h}, {-0.08, -0.28, 0.45 * h}, 0.05, 0.04, 6);
        b.frustum({-0.05, 0.26, 0.8 * h}, {0.08, 0.28, 0.45 * h}, 0.05, 0.04, 6);
        b.set_material(Material::kPlaster);  // skin and hair reflect like a matte wall
        b.ellipsoid({0.0, 0.0, 0.93 * h}, {0.1, 0.09, 0.07 * h});
        return mesh;
    }
    // Vehicles use the parked-vehicle models on flat ground.
    const Terrain flat(TerrainConfig{0.0, 100.0, 4.0},
                       Eigen::AlignedBox2d(Eigen::Vector2d(-8, -8), Eigen::Vector2d(8, 8)), 0);
    ObjectInstance o;
    o.id = id;
    o.kind = kind == ActorKind::kCar ? ObjectKind::kCar : ObjectKind::kVan;
    o.seed = seed;
    o.sink = 0.0;
    build_object(o, flat, mesh);
    return mesh;
}

}  // namespace ltm::sim
