#pragma once
// The robot's route in one session: driven waypoints (rounded corners, speed per leg, standing
// on the terrain) or a recorded trajectory file (KITTI poses and times).
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "simulator/core/geometry2d.hpp"
#include "simulator/core/scenario.hpp"
#include "simulator/core/terrain.hpp"

namespace ltm::sim {

class RobotPath {
  public:
    // Reads trajectory files (relative to base_dir). Throws ScenarioError with a one-line
    // message for missing or malformed files and unusable waypoints.
    RobotPath(const RouteConfig& config, const std::string& base_dir);

    bool from_file() const { return !poses_.empty(); }
    // Plan view of the route (for road corridors, actor paths and terrain coverage).
    const Polyline& centerline() const { return line_; }
    double duration() const;  // [s] route time from start to end
    // Plan position of the robot at route time t (clamped to the route).
    Eigen::Vector2d plan_position(double t) const;
    // Arc length along centerline() at route time t (clamped).
    double arc_at(double t) const;
    // Route time at which the robot passes waypoint i of route_laps() (the first lap's are the
    // configured ones, 0..n-1; waypoint routes; file routes: -1).
    double waypoint_time(int i) const;
    int num_waypoints() const { return static_cast<int>(waypoint_vertex_.size()); }
    // Route times of scans in [t0, t1]: every 1/rate s (waypoints) or the file's times.
    std::vector<double> scan_times(double t0, double t1, double rate) const;
    // Ground under a recorded path: T_world_sensor * (0, 0, -height) every ~2 m (file routes).
    std::vector<Eigen::Vector3d> ground_points(double height) const;
    // File routes: moves every pose vertically so the ground `height` below it is on the terrain.
    // Recorded heights disagree where a path comes back (KITTI 00: up to 0.5 m), so one ground
    // cannot pass through all of them; positions in plan, headings and tilts are kept.
    void drape(const Terrain& terrain, double height);
    // T_world_sensor at route time t. Waypoint routes stand on the terrain, the sensor `height`
    // above it along the ground normal.
    Eigen::Isometry3d pose_at(double t, const Terrain& terrain, double height) const;

  private:
    void init_waypoints(const RouteConfig& config);
    void init_file(const RouteConfig& config, const std::string& base_dir);

    Polyline line_;
    std::vector<double> vertex_time_;           // waypoint routes: time at each line_ vertex
    std::vector<std::size_t> waypoint_vertex_;  // waypoint i -> line_ vertex
    common::PoseList poses_;                    // file routes: T_world_lidar
    std::vector<double> times_;                 // file routes: time of each pose [s]
};

// The waypoints driven by a waypoint route: config.waypoints once, or config.laps times with a
// connecting leg between laps, straight from the last waypoint to the first. Where the robot
// would have to reverse (a turn over 120 deg at either end of the leg) it drives a turning loop
// ahead of it instead: out to 6 corner radii ahead and 2 to either side, back to the same point.
std::vector<Waypoint> route_laps(const RouteConfig& config);

// Resolves a scenario path: absolute as is, relative against base_dir.
std::string resolve_path(const std::string& path, const std::string& base_dir);

}  // namespace ltm::sim
