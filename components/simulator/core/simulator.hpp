#pragma once
// The simulated test world of one session, scan by scan: ray-cast LiDAR scans with their true
// poses and per-point labels, and the true static surfaces. A synchronous core: no threads, no
// I/O after construction, no middleware; an adapter publishes scans at the sensor rate.
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/core/ply_io.hpp"
#include "common/core/point_cloud.hpp"
#include "simulator/core/actors.hpp"
#include "simulator/core/objects.hpp"
#include "simulator/core/robot_path.hpp"
#include "simulator/core/scenario.hpp"
#include "simulator/core/sensor_model.hpp"
#include "simulator/core/session_changes.hpp"
#include "simulator/core/terrain.hpp"
#include "simulator/core/world.hpp"

namespace ltm::sim {

struct SimScan {
    std::size_t index = 0;              // scan number within the session
    common::PointCloud cloud;           // LiDAR frame; intensity; time when configured
    std::vector<std::uint32_t> labels;  // one per point (common/core/point_labels.hpp)
    std::vector<std::uint16_t> rings;   // one per point: beam (spinning) or laser (rosette)
    Eigen::Isometry3d T_world_lidar = Eigen::Isometry3d::Identity();  // true pose at the stamp
    bool after_kidnap = false;  // first scan after the robot was moved without being told
};

class Simulator {
  public:
    // Builds the world and plans the scans of session `session` (0-based). Loads trajectory
    // files. Throws ScenarioError (one line naming the key or file) on unusable input.
    explicit Simulator(const ScenarioConfig& scenario, int session = 0);

    std::size_t num_scans() const { return slots_.size(); }
    double stamp(std::size_t i) const { return slots_[i].stamp; }
    Eigen::Isometry3d pose(std::size_t i) const;  // T_world_lidar at stamp(i)
    // T_world_lidar dt seconds after stamp(i), within the sweep (for deskewing ground truth).
    Eigen::Isometry3d pose_at(std::size_t i, double dt) const;
    bool after_kidnap(std::size_t i) const { return slots_[i].kidnap; }

    // Scan i: a pure function of the scenario, its seed, the session and i (any order, any
    // thread). False when i is out of range.
    bool scan(std::size_t i, SimScan& out) const;
    // Sequential access from a cursor (starts at 0); false after the last scan.
    bool next_scan(SimScan& out);
    void seek(std::size_t i) { cursor_ = i; }

    // The session's true static surfaces: terrain and objects, no moving actors.
    common::PlyMesh truth_mesh() const;

    const ScenarioConfig& scenario() const { return scenario_; }
    int session() const { return session_; }
    const SensorModel& sensor() const { return sensor_; }
    const std::vector<ObjectInstance>& objects() const { return plan_.objects[session_]; }
    const SessionPlan& plan() const { return plan_; }
    const std::vector<Actor>& actors() const { return actors_; }
    const Terrain& terrain() const { return terrain_; }
    const World& world() const { return world_; }
    // Notes about the build: changes or actors that found too few places.
    const std::vector<std::string>& warnings() const { return warnings_; }

  private:
    struct Slot {
        double stamp;       // [s]
        double route_time;  // [s] along the session's route
        bool kidnap;
    };
    void plan_slots(const RobotPath& path);
    std::uint32_t label_of(const SurfaceHit& hit) const;
    float albedo(const SurfaceHit& hit, const Eigen::Vector3f& point) const;

    ScenarioConfig scenario_;
    int session_;
    SensorModel sensor_;
    std::unique_ptr<RobotPath> path_;
    Terrain terrain_;
    SessionPlan plan_;
    World world_;
    std::vector<Actor> actors_;
    std::vector<int> actor_prototype_;
    std::vector<std::uint16_t> class_of_;  // label class per static object id
    std::vector<Slot> slots_;
    std::vector<std::string> warnings_;
    std::uint64_t scan_key_ = 0;
    std::uint64_t albedo_key_ = 0;
    std::size_t cursor_ = 0;
};

// First id given to moving actors; static object ids stay below it.
constexpr std::uint16_t kFirstActorId = 0xF001;

}  // namespace ltm::sim
