#include "simulator/core/scenario.hpp"

#include <cmath>
#include <cstdio>

namespace ltm::sim {
namespace {

using common::ConfigChecker;
using namespace common::rules;

void check_sensor(const SensorConfig& s, ConfigChecker& k) {
    k("sensor.rate", s.rate_hz, positive);
    k("sensor.min_range", s.min_range, non_negative);
    k("sensor.max_range", s.max_range, positive);
    k.require(s.max_range > s.min_range, "sensor.max_range", "must exceed min_range");
    k("sensor.range_noise", s.range_noise, non_negative);
    k("sensor.dropout", s.dropout, unit);
    k("sensor.intensity_noise", s.intensity_noise, non_negative);
    k("sensor.range_at_10pct", s.range_at_10pct, positive);
    if (s.pattern == ScanPattern::kSpinning) {
        k.require(!s.elevations_deg.empty(), "sensor.elevations_deg",
                  "a spinning sensor needs beams");
        k.require(s.elevations_deg.size() <= 0xFFFF, "sensor.elevations_deg", "too many beams");
        k("sensor.columns", s.columns, at_least(1));
    } else {
        k("sensor.points_per_scan", s.points_per_scan, at_least(1));
        k("sensor.fov_deg", s.fov_deg, positive);
        k.require(s.fov_deg < 180, "sensor.fov_deg", "must be in (0, 180)");
        k("sensor.lasers", s.rosette_lasers, at_least(1));
    }
}

void check_world(const WorldConfig& w, ConfigChecker& k) {
    k("world.margin", w.margin, non_negative);
    k("world.road_width", w.road_width, positive);
    k("world.tree_density", w.tree_density, non_negative);
    k("world.terrain.cell", w.terrain.cell, at_least(0.25));
    k("world.terrain.wavelength", w.terrain.wavelength, positive);
    k("world.substation.bay_width", w.substation.bay_width, at_least(8));
    k("world.substation.fence_segment", w.substation.fence_segment, at_least(3));
    k("world.town.tree_spacing", w.town.tree_spacing, above(1));
    k("world.town.pole_spacing", w.town.pole_spacing, above(1));
}

// Unit direction of the route's leg into waypoint i (backwards: false) or out of it, skipping
// repeated points; zero where there is none.
Eigen::Vector2d leg_direction(const std::vector<Waypoint>& w, std::size_t i, bool forwards) {
    const Eigen::Vector2d p(w[i].x, w[i].y);
    if (forwards) {
        for (std::size_t j = i + 1; j < w.size(); ++j)
            if (const Eigen::Vector2d d(w[j].x - p.x(), w[j].y - p.y()); d.norm() > 1e-9)
                return d.normalized();
    } else {
        for (std::size_t j = i; j-- > 0;)
            if (const Eigen::Vector2d d(p.x() - w[j].x, p.y() - w[j].y); d.norm() > 1e-9)
                return d.normalized();
    }
    return Eigen::Vector2d::Zero();
}

// A turn on the spot at waypoint i ends on the heading of the leg out of it.
void check_spin(const RouteConfig& r, std::size_t i, const std::string& wk, ConfigChecker& k) {
    const Waypoint& w = r.waypoints[i];
    k(wk + ".spin_time", w.spin_time, non_negative);
    k.require(w.spin_deg == 0 || w.spin_time > 0, wk + ".spin", "needs a spin_time > 0");
    if (!(w.spin_time > 0)) return;
    const bool end = i == 0 || i + 1 == r.waypoints.size();
    k.require(!end || r.laps == 1, wk + ".spin",
              "a turn on the spot at the first or last waypoint needs laps: 1");
    Eigen::Vector2d in = leg_direction(r.waypoints, i, false);
    Eigen::Vector2d out = leg_direction(r.waypoints, i, true);
    if (in.isZero()) in = out;
    if (out.isZero()) out = in;
    const double turn = std::atan2(in.x() * out.y() - in.y() * out.x(), in.dot(out)) * 180.0 / M_PI;
    const double off = std::remainder(w.spin_deg - turn, 360.0);
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "must end on the next leg's heading: the route turns %.1f deg here (give that "
                  "plus whole turns, e.g. %.1f or %.1f)",
                  turn, turn - 360.0, turn + 360.0);
    k.require(std::abs(off) <= 1.0, wk + ".spin", buf);
}

void check_session(const SessionConfig& s, const std::string& key, ConfigChecker& k) {
    const RouteConfig& r = s.route;
    k.require(!r.poses_file.empty() || r.waypoints.size() >= 2, key + ".route",
              "needs two waypoints or a poses_file");
    k.require(r.poses_file.empty() || r.waypoints.empty(), key + ".route",
              "give waypoints or a poses_file, not both");
    k(key + ".route.speed", r.speed, positive);
    k(key + ".route.corner_radius", r.corner_radius, non_negative);
    k(key + ".route.laps", r.laps, at_least(1));
    k.require(r.laps == 1 || r.poses_file.empty(), key + ".route.laps",
              "only waypoint routes can be repeated");
    for (std::size_t i = 0; i < r.waypoints.size(); ++i) {
        const std::string wk = key + ".route.waypoints[" + std::to_string(i) + "]";
        k.require(r.waypoints[i].speed >= 0, wk, "speed must be >= 0");
        check_spin(r, i, wk, k);
    }
    for (std::size_t i = 0; i < s.kidnaps.size(); ++i) {
        const KidnapConfig& c = s.kidnaps[i];
        const std::string kk = key + ".kidnaps[" + std::to_string(i) + "]";
        k(kk + ".at", c.at, positive);
        k.require(c.resume_at >= 0 || c.resume_at_waypoint >= 0, kk,
                  "needs resume_at or resume_at_waypoint");
        k.require(c.resume_at < 0 || c.resume_at_waypoint < 0, kk,
                  "give resume_at or resume_at_waypoint, not both");
        k.require(c.resume_at_waypoint < static_cast<int>(r.waypoints.size()),
                  kk + ".resume_at_waypoint", "no such waypoint");
        k(kk + ".pause", c.pause, non_negative);
    }
    k(key + ".actors.vehicles", s.actors.vehicles, non_negative);
    k(key + ".actors.pedestrians", s.actors.pedestrians, non_negative);
    for (std::size_t i = 0; i < s.actors.placed.size(); ++i) {
        const ActorConfig& a = s.actors.placed[i];
        const std::string ak = key + ".actors.placed[" + std::to_string(i) + "]";
        k.require(a.waypoints.size() >= 2, ak + ".waypoints", "needs two points");
        k(ak + ".speed", a.speed, positive);
    }
    const ChangesConfig& c = s.changes;
    k(key + ".changes.move_parked", c.move_parked, non_negative);
    k(key + ".changes.remove_parked", c.remove_parked, non_negative);
    k(key + ".changes.add_parked", c.add_parked, non_negative);
    k(key + ".changes.add_containers", c.add_containers, non_negative);
    k(key + ".changes.remove_fence_segments", c.remove_fence_segments, non_negative);
}

}  // namespace

std::optional<common::ConfigProblem> validate_scenario(const ScenarioConfig& scenario) {
    ConfigChecker k;
    k.require(!scenario.sessions.empty(), "sessions", "the scenario needs at least one session");
    check_sensor(scenario.sensor, k);
    check_world(scenario.world, k);
    for (std::size_t i = 0; i < scenario.sessions.size(); ++i) {
        check_session(scenario.sessions[i], "sessions[" + std::to_string(i) + "]", k);
    }
    return k.problem();
}

}  // namespace ltm::sim
