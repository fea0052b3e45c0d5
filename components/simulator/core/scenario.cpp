#include "simulator/core/scenario.hpp"

namespace ltm::sim {
namespace {

std::string check_sensor(const SensorConfig& s) {
    if (!(s.rate_hz > 0)) return "sensor.rate: must be > 0";
    if (!(s.min_range >= 0 && s.max_range > s.min_range))
        return "sensor.max_range: must exceed min_range >= 0";
    if (!(s.range_noise >= 0)) return "sensor.range_noise: must be >= 0";
    if (!(s.dropout >= 0 && s.dropout <= 1)) return "sensor.dropout: must be in [0, 1]";
    if (!(s.intensity_noise >= 0)) return "sensor.intensity_noise: must be >= 0";
    if (!(s.range_at_10pct > 0)) return "sensor.range_at_10pct: must be > 0";
    if (s.pattern == ScanPattern::kSpinning) {
        if (s.elevations_deg.empty()) return "sensor.elevations_deg: a spinning sensor needs beams";
        if (s.elevations_deg.size() > 0xFFFF) return "sensor.elevations_deg: too many beams";
        if (s.columns < 1) return "sensor.columns: must be >= 1";
    } else {
        if (s.points_per_scan < 1) return "sensor.points_per_scan: must be >= 1";
        if (!(s.fov_deg > 0 && s.fov_deg < 180)) return "sensor.fov_deg: must be in (0, 180)";
        if (s.rosette_lasers < 1) return "sensor.lasers: must be >= 1";
    }
    return {};
}

std::string check_world(const WorldConfig& w) {
    if (!(w.margin >= 0)) return "world.margin: must be >= 0";
    if (!(w.road_width > 0)) return "world.road_width: must be > 0";
    if (!(w.tree_density >= 0)) return "world.tree_density: must be >= 0";
    if (!(w.terrain.cell >= 0.25)) return "world.terrain.cell: must be >= 0.25 m";
    if (!(w.terrain.wavelength > 0)) return "world.terrain.wavelength: must be > 0";
    if (!(w.substation.bay_width >= 8)) return "world.substation.bay_width: must be >= 8 m";
    if (!(w.substation.fence_segment >= 3)) return "world.substation.fence_segment: must be >= 3 m";
    if (!(w.town.tree_spacing > 1)) return "world.town.tree_spacing: must be > 1 m";
    if (!(w.town.pole_spacing > 1)) return "world.town.pole_spacing: must be > 1 m";
    return {};
}

std::string check_session(const SessionConfig& s, const std::string& key) {
    const RouteConfig& r = s.route;
    if (r.poses_file.empty() && r.waypoints.size() < 2)
        return key + ".route: needs two waypoints or a poses_file";
    if (!r.poses_file.empty() && !r.waypoints.empty())
        return key + ".route: give waypoints or a poses_file, not both";
    if (!(r.speed > 0)) return key + ".route.speed: must be > 0";
    if (!(r.corner_radius >= 0)) return key + ".route.corner_radius: must be >= 0";
    if (r.laps < 1) return key + ".route.laps: must be >= 1";
    if (r.laps > 1 && !r.poses_file.empty())
        return key + ".route.laps: only waypoint routes can be repeated";
    for (std::size_t i = 0; i < r.waypoints.size(); ++i) {
        if (r.waypoints[i].speed < 0)
            return key + ".route.waypoints[" + std::to_string(i) + "]: speed must be >= 0";
    }
    for (std::size_t i = 0; i < s.kidnaps.size(); ++i) {
        const KidnapConfig& k = s.kidnaps[i];
        const std::string kk = key + ".kidnaps[" + std::to_string(i) + "]";
        if (!(k.at > 0)) return kk + ".at: must be > 0";
        if (k.resume_at < 0 && k.resume_at_waypoint < 0)
            return kk + ": needs resume_at or resume_at_waypoint";
        if (k.resume_at >= 0 && k.resume_at_waypoint >= 0)
            return kk + ": give resume_at or resume_at_waypoint, not both";
        if (k.resume_at_waypoint >= static_cast<int>(r.waypoints.size()))
            return kk + ".resume_at_waypoint: no such waypoint";
        if (!(k.pause >= 0)) return kk + ".pause: must be >= 0";
    }
    if (s.actors.vehicles < 0 || s.actors.pedestrians < 0)
        return key + ".actors: counts must be >= 0";
    for (std::size_t i = 0; i < s.actors.placed.size(); ++i) {
        const ActorConfig& a = s.actors.placed[i];
        const std::string ak = key + ".actors.placed[" + std::to_string(i) + "]";
        if (a.waypoints.size() < 2) return ak + ".waypoints: needs two points";
        if (!(a.speed > 0)) return ak + ".speed: must be > 0";
    }
    const ChangesConfig& c = s.changes;
    if (c.move_parked < 0 || c.remove_parked < 0 || c.add_parked < 0 || c.add_containers < 0 ||
        c.remove_fence_segments < 0) {
        return key + ".changes: counts must be >= 0";
    }
    return {};
}

}  // namespace

std::string validate_scenario(const ScenarioConfig& scenario) {
    if (scenario.sessions.empty()) return "sessions: the scenario needs at least one session";
    if (std::string p = check_sensor(scenario.sensor); !p.empty()) return p;
    if (std::string p = check_world(scenario.world); !p.empty()) return p;
    for (std::size_t k = 0; k < scenario.sessions.size(); ++k) {
        if (std::string p =
                check_session(scenario.sessions[k], "sessions[" + std::to_string(k) + "]");
            !p.empty()) {
            return p;
        }
    }
    return {};
}

}  // namespace ltm::sim
