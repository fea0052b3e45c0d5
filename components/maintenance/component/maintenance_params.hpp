#pragma once
// The maintenance component's parameters: its own keys (what it listens to, how often it
// maintains, where it writes) beside the keys of the core's MaintenanceConfig (`voxel_size`,
// `change.sigma`, `ground.height`, ...: visit_fields in maintenance/core/maintenance_config.hpp).
// Wrong types and invalid values fail with file, line and key; the host refuses the keys nobody
// read.
#include <cstdint>
#include <string>

#include "maintenance/core/maintenance_config.hpp"
#include "maintenance/core/view_spacing.hpp"
#include "runtime/parameters.hpp"

namespace ltm::maintenance {

enum class PoseInput {
    kOdometry,            // nav_msgs/Odometry on `odometry` (remap: corrected_odometry)
    kPose,                // geometry_msgs/PoseStamped on `pose` (e.g. ground_truth)
    kPoseWithCovariance,  // geometry_msgs/PoseWithCovarianceStamped on `pose` (localisation)
};

struct MaintenanceComponentConfig {
    PoseInput input = PoseInput::kOdometry;
    std::string output_dir;          // "" : publish only; else created when missing
    double maintain_every_s = 30.0;  // [s] of scan time between passes (0: only at shutdown)
    // The maintained map (LongTermMap::save/load): loaded when the file exists (this run is
    // then another session on it), saved at shutdown. "": kept in memory only.
    std::string map_file;
    // A site's folder (map/core/site_store.hpp) instead of map_file: the maintained map is loaded
    // from the start version's (`site_version`, or the newest intact one; none: a new map) and
    // saved into the site's staging (SITE/next/maintenance/long_term_map.bin), which the `site`
    // component commits as the next version.
    std::string site_dir;
    std::string site_version;
    int session = -1;  // this run's session number on the map (-1: the loaded map's last + 1, or 0)
    int max_queue = 50;            // scans waiting for the worker
    bool skip_while_busy = false;  // a full queue drops its oldest scan (live) or waits (offline)
    // A scan that finds this many or more waiting (a pass runs) waits packed: lossless, 62 % of
    // the memory on real scans (maintenance/core/packed_scan.hpp); 0: always, -1: never.
    int pack_after = 10;
    // The worker's CPU at most this share of one core (common/core/cpu_pacer.hpp, a bucket of 0.1
    // s): a pass is spread over time between its regions, and the scans after it too, rather than a
    // burst of seconds (live). 1: as fast as it goes (offline).
    double cpu_share = 1.0;
    // A CPU budget shared with the process's other background work (common/core/cpu_budget.hpp:
    // e.g. the mapping's `cpu_budget`, the same name): the worker draws from it, cpu_share being
    // its share of one core (every component naming it gives the same). "": a budget of its own.
    std::string cpu_budget;
    // The waiting scans' memory at most this [MiB] besides max_queue scans (a 64-beam scan waits
    // in ~0.9 MiB packed: 300 of them ~270 MiB); a VLP-32C's 300 scans take ~105 MiB. A full queue
    // does what max_queue does (the oldest dropped live, the sensor waits offline), logged. 0: no
    // bound but the count.
    double max_queue_mb = 128.0;
    // Paging (maintenance/core/region_pager.hpp): regions of the maintained map farther than
    // paging_radius [m] from the robot wait on disk in paging_dir until the robot comes back
    // (a loaded map's regions all start there). 0: the whole map in memory. paging_dir "":
    // OUTPUT_DIR/paged_regions, or without output_dir a folder of the system's temporary one.
    double paging_radius = 100.0;
    std::string paging_dir;
    // Which scans are taken (maintenance/core/view_spacing.hpp): `view_distance` [m] (0: every
    // scan), `view_angle` [deg], `view_interval_s` [s]. On the robot (robot_lifelong.yaml) a
    // scan every 0.4 m halves the worker's CPU at 2 m/s; the default keeps every scan.
    ViewSpacingConfig views;
    MaintenanceConfig maintenance;
};

// Throws ConfigError naming file, line and key.
MaintenanceComponentConfig load_maintenance_params(runtime::Parameters& params);

}  // namespace ltm::maintenance
