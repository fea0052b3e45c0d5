#pragma once
// Loading trajectories for the subcommands: KITTI or TUM files, KITTI camera or LiDAR frames.
#include <string>

#include "common/core/trajectory_io.hpp"

namespace ltm::eval::cli {

struct LoadedTrajectory {
    common::Trajectory poses;  // KITTI files: stamps from times.txt if given, else the index
    bool stamped = false;      // TUM file (real stamps)
};

// `format` kitti|tum.
LoadedTrajectory load_trajectory(const std::string& path, const std::string& format);

// Converts poses between `from` and `to` (lidar|camera) with the Tr of a KITTI calib.txt;
// throws UsageError when a conversion is needed and `calib` is empty.
common::PoseList convert_frame(const common::PoseList& poses, const std::string& from,
                               const std::string& to, const std::string& calib);

}  // namespace ltm::eval::cli
