#pragma once
// A simulated test world: the site, the sensor, and one or more sessions (robot route, kidnaps,
// moving actors, changes since the first session). Loaded from YAML by load_scenario() or built
// by hand in tests; every field has a default and a unit.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "common/core/one_line.hpp"
#include "simulator/core/geometry2d.hpp"
#include "simulator/core/objects.hpp"
#include "simulator/core/sensor_model.hpp"
#include "simulator/core/terrain.hpp"

namespace ltm::sim {

// A scenario that cannot be used. what() is one line naming the key or file at fault (control
// characters quoted from the file are escaped).
class ScenarioError : public std::runtime_error {
  public:
    explicit ScenarioError(const std::string& what) : std::runtime_error(common::one_line(what)) {}
};

enum class WorldStyle { kSubstation, kTown };

struct SubstationConfig {
    Eigen::AlignedBox2d yard{Eigen::Vector2d(0, 0), Eigen::Vector2d(240, 150)};  // fenced [m]
    double bay_width = 22.0;         // [m] width of one equipment bay (bays run along y)
    double equipment_density = 0.9;  // chance that an equipment slot is filled
    double fence_segment = 18.0;     // [m] length of one fence object (a unit of change)
    Eigen::AlignedBox2d parking;     // [m] car park (empty box: none)
    double parking_occupancy = 0.6;  // chance that a parking space holds a vehicle
};

struct TownConfig {
    double parked_car_probability = 0.5;  // chance that a kerb space holds a car
    double tree_spacing = 14.0;           // [m] along each side of a street
    double pole_spacing = 35.0;           // [m]
    double building_probability = 0.85;   // chance that a building lot is built on
    double second_row_probability = 0.5;  // chance of a building behind the first row
};

struct PlacedObject {
    ObjectKind kind = ObjectKind::kBuilding;
    double x = 0.0, y = 0.0;                         // [m] centre
    double yaw_deg = 0.0;                            // [deg]
    Eigen::Vector3d size = Eigen::Vector3d::Zero();  // [m] length, width, height; 0: default
    bool parked = false;  // a vehicle that later sessions may move or remove
};

struct WorldConfig {
    WorldStyle style = WorldStyle::kSubstation;
    double margin = 80.0;       // [m] of scenery beyond the routes
    double road_width = 7.0;    // [m] kept clear around every robot route
    double tree_density = 1.0;  // trees per 1000 m^2 of open land outside sites and streets
    TerrainConfig terrain;
    SubstationConfig substation;
    TownConfig town;
    std::vector<PlacedObject> objects;  // placed before the procedural content
};

struct Waypoint {
    double x = 0.0, y = 0.0;  // [m]
    double speed = 0.0;       // [m/s] on the leg that starts here; 0: the route's speed
    // Turning on the spot (when spin_time > 0): the robot stops here and turns by spin_deg
    // (positive: left, counter-clockwise) at a constant rate for spin_time seconds, then drives
    // on. The corner here is not rounded. spin_deg must end on the next leg's heading: the
    // route's turn here plus whole turns, within 1 deg (the nearest such angle is turned).
    // spin_deg 0 with a spin_time: the robot stands still that long.
    double spin_deg = 0.0;   // [deg]
    double spin_time = 0.0;  // [s]
};

struct RouteConfig {
    std::vector<Waypoint> waypoints;  // either waypoints ...
    double speed = 1.5;               // [m/s]
    double corner_radius = 3.0;       // [m] corners are driven as arcs
    std::string poses_file;           // ... or a trajectory file (KITTI 3x4 poses, one a line)
    std::string times_file;           // one time [s] a pose
    std::string calib_file;           // KITTI calib.txt: camera-frame poses become Tr^-1 P Tr
    bool camera_frame = true;  // poses_file holds camera-frame poses (then calib_file is needed)
    // Waypoint routes: driven this many times. Between laps the robot drives straight from the
    // last waypoint back to the first; where that would reverse its heading it turns in a loop
    // ahead of it (route_laps() in robot_path.hpp).
    int laps = 1;
};

// The robot is lifted at route time `at`, carried without the system being told, and put down
// where the route is at `resume_at` (or at waypoint `resume_at_waypoint`); scans resume `pause`
// seconds later.
struct KidnapConfig {
    double at = 0.0;          // [s] route time
    double resume_at = -1.0;  // [s] route time; < 0: use resume_at_waypoint
    int resume_at_waypoint = -1;
    double pause = 3.0;  // [s]
};

enum class ActorKind { kCar, kVan, kPedestrian };

struct ActorConfig {
    ActorKind kind = ActorKind::kPedestrian;
    Points2 waypoints;          // walked or driven back and forth
    double speed = 1.4;         // [m/s]
    double start_offset = 0.0;  // [m] along the path at the session start
};

struct ActorsConfig {
    int vehicles = 0;     // procedural moving vehicles along the route (opposite lane)
    int pedestrians = 0;  // procedural pedestrians beside the route
    std::vector<ActorConfig> placed;
};

// Differences from the first session (ignored in the first session).
struct ChangesConfig {
    int move_parked = 0;            // parked vehicles that stand elsewhere
    int remove_parked = 0;          // parked vehicles that are gone
    int add_parked = 0;             // vehicles parked where there were none
    int add_containers = 0;         // new containers beside the route
    int remove_fence_segments = 0;  // fence objects taken down
    std::vector<PlacedObject> add;  // placed new objects
    Points2 remove_at;              // remove the object standing at each point
};

struct SessionConfig {
    std::string name = "session";
    double start_time = 0.0;  // [s] stamp of the session start (days later: 86400 s a day)
    RouteConfig route;
    std::vector<KidnapConfig> kidnaps;
    bool kidnapped_start = false;  // the start pose is unknown to the system (ground truth note)
    ActorsConfig actors;
    ChangesConfig changes;
};

struct ScenarioConfig {
    std::string name = "scenario";
    std::uint64_t seed = 1;
    SensorConfig sensor;
    WorldConfig world;
    std::vector<SessionConfig> sessions;
    std::string base_dir = ".";  // relative file paths are resolved against this folder
};

// The first problem, naming the key as in the scenario YAML (e.g. "sessions[1].route.speed");
// nullopt when usable.
std::optional<common::ConfigProblem> validate_scenario(const ScenarioConfig& scenario);

}  // namespace ltm::sim
