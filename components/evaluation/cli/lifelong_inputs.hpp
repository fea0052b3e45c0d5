#pragma once
// What `ltm_eval lifelong` reads from a day's folder of a lifelong benchmark run besides
// trajectories and objects: kidnap stamps, the host's /usr/bin/time -v report, sizes on disk and
// the voxels of a saved map.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::eval::cli {

// ltm_sim's kidnaps.txt: `frame stamp` a line, `#` comments. Throws common::IoError.
std::vector<double> read_kidnap_stamps(const std::string& path);

// GNU time -v: peak resident memory and CPU time of the process it ran.
struct ProcessUsage {
    bool valid = false;
    double max_rss_mb = 0.0;  // [MiB] "Maximum resident set size (kbytes)"
    double cpu_s = 0.0;       // [s] user + system
};
// An empty result (valid false) when the file is missing or lacks the lines.
ProcessUsage read_time_report(const std::string& path);

// Bytes of a file, or of every regular file under a folder (links followed); 0 when absent.
std::uintmax_t bytes_on_disk(const std::string& path);

// The centres of the voxels localisation would use of the map in `dir` (ltm::map::merge_voxels
// with the given filter), each mapped by T_world_map. Throws when the map cannot be loaded.
std::vector<Eigen::Vector3d> map_voxel_centres(const std::string& dir,
                                               const Eigen::Isometry3d& T_world_map,
                                               double min_health, double min_planarity);

}  // namespace ltm::eval::cli
