#pragma once
// The maintained map (METHOD.md section 5): sessions of registered scans, on one map, in square
// regions of the map frame. Each scan adds its points to the regions' voxels and, every
// view_spacing seconds (derived_thresholds.hpp when unset), becomes a view (its range image)
// that judges the voxels in its range view_delay seconds later (so the voxels a moving object
// leaves behind it exist by then).
// maintain() runs the change decisions region by region and erases what is gone.
//
// Paging (set_paging, region_pager.hpp): only the regions near the robot are in memory, the rest
// on disk until a scan or a view reaches them; what the map decides is the same either way.
//
// Map time: the stamps of a session, shifted so that each session starts session_gap seconds
// after the previous one ended (days between sessions would swamp seconds within them).
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "maintenance/core/change_detector.hpp"
#include "maintenance/core/change_set.hpp"
#include "maintenance/core/motion_tracker.hpp"
#include "maintenance/core/observation_map.hpp"
#include "maintenance/core/region_pager.hpp"

namespace ltm::maintenance {

struct LongTermMapStats {
    std::size_t regions = 0, voxels = 0, views = 0, views_pending = 0;
    std::size_t memory_bytes = 0;  // the regions in memory, the pending views and the motion
    std::size_t views_bytes = 0;   // of it: the pending views' range images
    std::size_t motion_bytes = 0;  // of it: the motion tracker's
    // Paging: regions (and their voxels, included in `voxels`) on disk, the bytes of their files,
    // regions written out and read back since the start.
    std::size_t regions_paged = 0, voxels_paged = 0, paged_bytes = 0;
    std::size_t pages_out = 0, pages_in = 0;
    double judge_ms = 0.0;   // total time views spent judging voxels
    double motion_ms = 0.0;  // total time the motion tracker took
    MotionStats motion;
    std::size_t voxels_flagged_moving = 0;  // flags set by the motion tracker (a voxel each time)
};

class LongTermMap {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    explicit LongTermMap(const MaintenanceConfig& config);
    // From now on only the regions within paging.radius of the robot stay in memory (radius 0:
    // every region, the default). Throws common::IoError when the folder cannot be made, and
    // common::ConfigError when a radius comes without a folder.
    void set_paging(const PagingConfig& paging);

    const MaintenanceConfig& config() const { return config_; }
    // The configuration the next pass decides with: the keys left unset filled from what the
    // current session has shown (derived_thresholds.hpp), the explicit ones as given.
    MaintenanceConfig decision_config() const;

    // Starts a session whose first scan has `first_stamp`; the views of the previous one are
    // judged first.
    void begin_session(std::uint32_t session, double first_stamp);
    std::uint32_t session() const { return session_; }
    double map_time() const { return now_; }
    double map_time_of(double stamp) const;  // in the current session

    // A registered scan: points in the sensor frame, the sensor's world pose, its stamp.
    // Non-finite points are skipped; points beyond max_range are not mapped. With
    // motion.enabled, the points of objects seen moving (motion_tracker.hpp) flag their voxels
    // kMoving: the next pass removes them (change_detector.hpp). `between` (optional) runs after
    // each region a view judged, each region paged in for the scan and each paged out: the
    // caller's chance to spread a scan's work over time (a view after a kidnap pages in and judges
    // a dozen regions: 0.6 s of CPU in one piece, issue 28); the result is the same as long as it
    // does not touch the map.
    void add_scan(const std::vector<Eigen::Vector3f>& points,
                  const Eigen::Isometry3d& T_world_sensor, double stamp,
                  const std::function<void()>& between = {});

    // Every pending view judges the voxels now.
    void flush_views();
    // Change decisions over the regions views judged since the last pass (after flush_views()); the
    // gone voxels are erased. `between` (optional) runs after each region but the last and
    // between a region's steps (maintain_region): the caller's chance to spread a pass over time
    // (common/core/cpu_pacer.hpp); the result is the same as long as it does not touch the map.
    ChangeSet maintain(const std::function<void()>& between = {});
    // End of a session: flush_views() then maintain().
    ChangeSet end_session();

    // The next three look at the regions in memory (every region without paging; page_in_all()).
    // True when the map keeps the voxel holding p (world frame): it exists and was not erased.
    bool keeps(const Eigen::Vector3f& p) const;
    // Flags of the voxel holding p (kGround, kNew), or nothing when it is not in the map.
    const ObservedVoxel* voxel_at(const Eigen::Vector3f& p) const;
    // Centres of every voxel (world frame).
    std::vector<Eigen::Vector3f> voxel_centres() const;
    // Every paged-out region back in memory (paging stays on: the next scan may page out again).
    void page_in_all();

    LongTermMapStats stats() const;

    // The map on disk (long_term_map_io.cpp): voxels, their histories and the map clock, in one
    // file with a CRC-32 a section, written atomically. Views still pending are not saved: call
    // end_session() first. load() refuses a damaged file, or one made with another voxel size,
    // region size or slot, with one line (common::IoError / FormatError) and returns nothing.
    // Both go a region at a time (the file is never whole in memory); with `paging`, load() puts
    // every region on disk as it reads it, to come back when the robot approaches.
    void save(const std::string& path) const;
    static LongTermMap load(const std::string& path, const MaintenanceConfig& config,
                            const PagingConfig& paging = {});
    // Sessions that built the map, in order.
    const std::vector<std::uint32_t>& sessions() const { return sessions_; }

  private:
    Eigen::Vector2i region_of(const Eigen::Vector3f& p) const;
    ObservationMap& region(const Eigen::Vector2i& key);  // created, or paged in, when missing
    bool within(const RegionKey& key, const Eigen::Vector2f& p, float reach) const;
    void judge(const View& view, const std::function<void()>& between = {});
    void follow_motion(const std::vector<Eigen::Vector3f>& points,
                       const Eigen::Isometry3d& T_world_sensor, double map_time);
    // Regions beyond the radius to disk (`between` after each).
    void page_far(const Eigen::Vector3d& sensor, const std::function<void()>& between = {});

    double paging_radius_ = 0.0;
    std::unique_ptr<RegionPager> pager_;

    MaintenanceConfig config_;
    std::map<std::pair<int, int>, std::unique_ptr<ObservationMap>> regions_;
    std::deque<View> pending_;
    std::set<std::pair<int, int>> dirty_;  // regions judged since the last maintain()
    std::uint32_t session_ = 0;
    bool in_session_ = false;
    double session_start_stamp_ = 0.0, session_offset_ = 0.0, now_ = 0.0;
    double last_view_time_ = -1e300;
    std::uint64_t next_view_ = 0, next_change_ = 1;
    std::size_t views_ = 0, session_views_ = 0;
    double judge_ms_ = 0.0, motion_ms_ = 0.0;
    MotionTracker motion_;
    std::size_t flagged_moving_ = 0;
    std::vector<std::uint32_t> sessions_;
    // Regions that held voxels when the session began (in memory or paged): create_range acts
    // there (config.create_range).
    std::set<std::pair<int, int>> mapped_before_;
};

}  // namespace ltm::maintenance
