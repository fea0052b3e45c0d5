#pragma once
// Which scans maintenance takes (issue 28: the robot's budget). Maintenance judges voxels over
// many views and sessions; at walking speed a 10 Hz sensor's consecutive scans see the same
// voxels from nearly the same place, and each costs the maintenance worker as much as the
// odometry's whole registration. A scan is taken when it is the first, when the sensor moved at
// least `distance` or turned at least `angle_deg` since the last one taken, or when `interval_s`
// passed since it (a robot standing still still sees what moves around it). distance 0: every
// scan (the default: a short window keeps all its views). No I/O.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>

namespace ltm::maintenance {

struct ViewSpacingConfig {
    double distance = 0.0;    // [m] 0: every scan
    double angle_deg = 10.0;  // [deg] a turn this large is a new view
    double interval_s = 1.0;  // [s] of scan time: at least one scan this often
};

// The first problem of a config ("view_distance: must be >= 0"), or none.
std::optional<std::string> validate(const ViewSpacingConfig& c);

class ViewSpacing {
  public:
    explicit ViewSpacing(ViewSpacingConfig config = {}) : config_(config) {}

    // Whether the scan at `stamp` [s] with this pose is taken (then it is the last taken).
    bool take(double stamp, const Eigen::Isometry3d& T_world_sensor);

    std::uint64_t taken() const { return taken_; }
    std::uint64_t left_out() const { return left_out_; }
    const ViewSpacingConfig& config() const { return config_; }

  private:
    ViewSpacingConfig config_;
    bool has_last_ = false;
    double last_stamp_ = 0.0;
    Eigen::Isometry3d last_pose_ = Eigen::Isometry3d::Identity();
    std::uint64_t taken_ = 0, left_out_ = 0;
};

}  // namespace ltm::maintenance
