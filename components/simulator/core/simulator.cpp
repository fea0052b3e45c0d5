#include "simulator/core/simulator.hpp"

#include <algorithm>
#include <cmath>

#include "common/core/point_labels.hpp"
#include "simulator/core/layout.hpp"

namespace ltm::sim {
namespace {

StreetProfile street_profile(const WorldConfig& w) {
    StreetProfile s;
    if (w.style == WorldStyle::kTown) {
        s.vehicle_offset = 3.4;
        s.walk_min = 6.3;
        s.walk_max = 7.2;
    } else {
        s.vehicle_offset = 2.7;
        s.walk_min = 0.5 * w.road_width + 0.8;
        s.walk_max = 0.5 * w.road_width + 1.6;
    }
    return s;
}

std::string session_key(int k) { return "sessions[" + std::to_string(k) + "]"; }

}  // namespace

Simulator::Simulator(const ScenarioConfig& scenario, int session)
    : scenario_(scenario), session_(session), sensor_(scenario.sensor) {
    if (const auto problem = validate_scenario(scenario_)) {
        throw ScenarioError(problem->key + ": " + problem->problem);
    }
    const int n_sessions = static_cast<int>(scenario_.sessions.size());
    if (session < 0 || session >= n_sessions) {
        throw ScenarioError("session " + std::to_string(session) + ": the scenario has " +
                            std::to_string(n_sessions) + " session(s), numbered from 0");
    }
    // Every session's route and actors shape the one static world.
    std::vector<std::unique_ptr<RobotPath>> paths;
    std::vector<Points2> routes;
    std::vector<std::vector<ActorConfig>> actor_configs;
    LayoutInputs inputs;
    inputs.sensor_range = scenario_.sensor.max_range;
    const StreetProfile street = street_profile(scenario_.world);
    for (int k = 0; k < n_sessions; ++k) {
        const SessionConfig& s = scenario_.sessions[static_cast<std::size_t>(k)];
        try {
            paths.push_back(std::make_unique<RobotPath>(s.route, scenario_.base_dir));
        } catch (const ScenarioError& e) {
            throw ScenarioError(session_key(k) + "." + e.what());
        }
        // The site is the same however often a route is driven: a route of N laps shapes the
        // world (along-route equipment, the terrain's extent, the changes, its actors, the draws
        // of the one random sequence that places everything) as its first lap does, and the
        // later laps and the legs between them are only kept clear. The first lap's actors go on
        // back and forth along their paths through the later laps (drawn not to meet the robot
        // on the first). (Shaped by all laps, a 3-lap site_loop was another site: 527 of its 724
        // objects elsewhere, and another day's scans of the 1-lap site localised 1/31 on its
        // map.)
        std::unique_ptr<RobotPath> one_lap;
        if (s.route.laps > 1) {
            RouteConfig first = s.route;
            first.laps = 1;
            one_lap = std::make_unique<RobotPath>(first, scenario_.base_dir);
            inputs.clearings.push_back(paths.back()->centerline().points());
        }
        const RobotPath& site_route = one_lap ? *one_lap : *paths.back();
        routes.push_back(site_route.centerline().points());
        inputs.robot_paths.push_back(routes.back());
        const auto g = paths.back()->ground_points(scenario_.sensor.height);
        inputs.ground.insert(inputs.ground.end(), g.begin(), g.end());
        int left_out = 0;
        actor_configs.push_back(make_session_actors(
            s.actors, site_route, street,
            hash_mix(scenario_.seed, 0xAC, static_cast<std::uint64_t>(k)), &left_out));
        if (left_out > 0) {
            warnings_.push_back(session_key(k) + ".actors: " + std::to_string(left_out) +
                                " procedural actor(s) left out (every path tried met the robot)");
        }
        for (const auto& a : actor_configs.back()) {
            inputs.actor_paths.emplace_back(a.waypoints, Actor(0, a).half_width());
        }
    }
    Layout layout = build_layout(scenario_.world, scenario_.seed, inputs);
    plan_ = plan_sessions(layout, scenario_.sessions, routes, scenario_.seed);
    warnings_.insert(warnings_.end(), plan_.warnings.begin(), plan_.warnings.end());
    const std::uint32_t max_id =
        std::max(layout.next_id, plan_.changed_ids.empty() ? 0u : plan_.changed_ids.back() + 1);
    if (max_id + 8 >= kFirstActorId) {
        throw ScenarioError("world: " + std::to_string(max_id) +
                            " objects exceed the label format's " + std::to_string(kFirstActorId) +
                            " (reduce margin or densities)");
    }
    class_of_.assign(max_id + 1, common::kSimStatic);
    for (const std::uint32_t id : plan_.changed_ids) class_of_[id] = common::kSimChangedObject;

    terrain_ = std::move(layout.terrain);
    Mesh mesh;
    terrain_.append_mesh(mesh, [&](const Eigen::Vector2d& p) { return layout.ground_material(p); });
    for (const auto& o : plan_.objects[static_cast<std::size_t>(session)])
        build_object(o, terrain_, mesh);
    world_ = World(std::move(mesh));

    const auto& configs = actor_configs[static_cast<std::size_t>(session)];
    if (configs.size() > 0xFFFFu - kFirstActorId)
        throw ScenarioError(session_key(session) + ".actors: too many actors");
    for (std::size_t j = 0; j < configs.size(); ++j) {
        const auto id = static_cast<std::uint16_t>(kFirstActorId + j);
        actors_.emplace_back(id, configs[j]);
        actor_prototype_.push_back(
            world_.add_prototype(actor_mesh(configs[j].kind, id, scenario_.seed)));
    }
    path_ = std::move(paths[static_cast<std::size_t>(session)]);
    if (path_->from_file()) path_->drape(terrain_, scenario_.sensor.height);
    plan_slots(*path_);
    scan_key_ = hash_mix(scenario_.seed, 0x5CA9, static_cast<std::uint64_t>(session));
    albedo_key_ = hash_mix(scenario_.seed, 0xA1BED0);
}

void Simulator::plan_slots(const RobotPath& path) {
    const SessionConfig& s = scenario_.sessions[static_cast<std::size_t>(session_)];
    const double period = sensor_.period();
    std::vector<KidnapConfig> kidnaps = s.kidnaps;
    std::sort(kidnaps.begin(), kidnaps.end(),
              [](const auto& a, const auto& b) { return a.at < b.at; });
    double route_start = 0.0, real_start = s.start_time;
    for (std::size_t k = 0; k <= kidnaps.size(); ++k) {
        const double route_end = k < kidnaps.size() ? kidnaps[k].at : path.duration();
        // A sweep must fit before the robot is lifted (file routes: scans at the file's times).
        const double last = path.from_file() ? route_end : route_end - period;
        bool first = true;
        for (const double t : path.scan_times(route_start, last, scenario_.sensor.rate_hz)) {
            const bool kidnap = first && (k > 0 || s.kidnapped_start);
            slots_.push_back({real_start + (t - route_start), t, kidnap});
            first = false;
        }
        if (k == kidnaps.size()) break;
        const KidnapConfig& kid = kidnaps[k];
        real_start += (route_end - route_start) + kid.pause;
        route_start =
            kid.resume_at >= 0 ? kid.resume_at : path.waypoint_time(kid.resume_at_waypoint);
        if (route_start < 0 || route_start >= path.duration()) {
            throw ScenarioError(session_key(session_) + ".kidnaps[" + std::to_string(k) +
                                "]: resume point is not on the route");
        }
    }
    for (std::size_t i = 1; i < slots_.size(); ++i) {
        if (slots_[i].stamp <= slots_[i - 1].stamp) {
            throw ScenarioError(session_key(session_) +
                                ".kidnaps: scan times would not increase (order kidnaps by time)");
        }
    }
}

Eigen::Isometry3d Simulator::pose(std::size_t i) const {
    return path_->pose_at(slots_[i].route_time, terrain_, scenario_.sensor.height);
}

Eigen::Isometry3d Simulator::pose_at(std::size_t i, double dt) const {
    return path_->pose_at(slots_[i].route_time + dt, terrain_, scenario_.sensor.height);
}

bool Simulator::next_scan(SimScan& out) {
    if (!scan(cursor_, out)) return false;
    ++cursor_;
    return true;
}

common::PlyMesh Simulator::truth_mesh() const {
    common::PlyMesh m;
    m.vertices = world_.static_mesh().vertices;
    m.triangles = world_.static_mesh().triangles;
    return m;
}

std::uint32_t Simulator::label_of(const SurfaceHit& hit) const {
    if (hit.actor)
        return common::make_label(common::kSimMovingActor, static_cast<std::uint16_t>(hit.object));
    const std::uint16_t cls =
        hit.object < class_of_.size() ? class_of_[hit.object] : common::kSimStatic;
    return common::make_label(cls, static_cast<std::uint16_t>(hit.object));
}

}  // namespace ltm::sim
