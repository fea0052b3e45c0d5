#pragma once
// The robot's route in one session: driven waypoints (rounded corners, speed per leg, turns on
// the spot, standing on the terrain) or a recorded trajectory file (KITTI poses and times).
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
    // configured ones, 0..n-1; waypoint routes; file routes: -1). A turn on the spot there
    // starts at that time.
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
    // A turn on the spot at arc length s, from route time t0 for `duration` s.
    struct Spin {
        double s = 0.0;
        std::size_t vertex = 0;  // line_ vertex
        double t0 = 0.0, duration = 0.0;
        double yaw0 = 0.0, angle = 0.0;  // [rad] heading at the start, turn (left positive)
    };
    // Where route time t is among the spins: drive time (spinning taken out), the spin under way
    // (-1: none) and how many spins are over.
    struct Phase {
        double drive_time = 0.0;
        int spinning = -1;
        std::size_t done = 0;
    };
    void init_waypoints(const RouteConfig& config);
    void init_file(const RouteConfig& config, const std::string& base_dir);
    Phase phase(double t) const;
    double arc_at_drive_time(double drive_time) const;
    // Heading of the line at s [rad], from the line between lo and hi (turns on the spot are not
    // smoothed over).
    double heading_at(double s, double lo, double hi) const;

    Polyline line_;
    std::vector<double> vertex_time_;           // waypoint routes: drive time at each line_ vertex
    std::vector<Spin> spins_;                   // waypoint routes: turns on the spot, in time order
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
