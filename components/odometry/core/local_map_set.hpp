#pragma once
// The active local maps of the odometry (METHOD.md Eq. 9): the newest is the registration target;
// when the sensor leaves the switch box around its anchor a new map starts at the current pose,
// seeded with the voxels of the current one that fall in its box, so registration never faces an
// empty map. Older maps stay active (a point in several boxes updates each one) until more than
// `max_active_maps` exist; then the oldest is finished and waits to be taken. Memory is bounded by
// the active maps plus the finished maps not yet taken.
#include <Eigen/Geometry>
#include <deque>
#include <vector>

#include "odometry/core/local_map.hpp"
#include "odometry/core/odometry_config.hpp"

namespace ltm::odometry {

class LocalMapSet {
  public:
    explicit LocalMapSet(const OdometryConfig& config);

    bool empty() const { return active_.empty(); }
    // The registration target (the newest map). Requires !empty().
    const LocalMap& current() const { return active_.back(); }
    const std::deque<LocalMap>& active() const { return active_; }

    // Integrates a scan (points in the LiDAR frame, sensor at T_odom_lidar). Starts the first map,
    // or a new one when the sensor has left the switch box of the current map's anchor.
    // Returns true when a new map was started.
    bool integrate(const std::vector<Eigen::Vector3f>& points,
                   const Eigen::Isometry3d& T_odom_lidar, double stamp);

    // Ends every active map (end of a run); they join the finished ones.
    void finish_all();
    // The odometry lost track: ends every active map and starts a new segment; the next
    // integrate() starts its first map, unseeded (nothing of the old maps is trusted in it).
    void start_new_segment();
    std::uint32_t segment() const { return segment_; }
    std::vector<LocalMap> take_finished();
    std::size_t finished_pending() const { return finished_.size(); }
    std::size_t memory_bytes() const;

  private:
    bool left_switch_box(const Eigen::Isometry3d& T_odom_lidar) const;

    OdometryConfig config_;
    std::uint32_t next_id_ = 0;
    std::uint32_t segment_ = 0;
    std::deque<LocalMap> active_;
    std::vector<LocalMap> finished_;
    std::vector<Eigen::Vector3f> scratch_;  // the scan in a map's frame
};

}  // namespace ltm::odometry
