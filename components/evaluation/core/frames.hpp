#pragma once
// Trajectory frames and pairing: KITTI camera <-> LiDAR poses, and pairing TUM trajectories by
// time stamp.
#include "common/core/trajectory_io.hpp"

namespace ltm::eval {

// T_cam_lidar = Tr of a KITTI calib.txt. Camera-frame poses (KITTI ground truth,
// T_cam0_camk) to LiDAR-frame poses T_lidar0_lidark = Tr^-1 P Tr (= common::camera_to_lidar_poses),
// and back: P = Tr L Tr^-1.
common::PoseList camera_to_lidar(const common::PoseList& camera_poses,
                                 const Eigen::Isometry3d& T_cam_lidar);
common::PoseList lidar_to_camera(const common::PoseList& lidar_poses,
                                 const Eigen::Isometry3d& T_cam_lidar);

// Pairs every estimate stamp with the nearest reference stamp within max_dt [s] (each reference
// pose used at most once, estimate order kept). Stamps need not be sorted.
struct PairedPoses {
    common::PoseList estimate, reference;
    std::vector<double> stamps;  // the estimate's stamps of the pairs
    std::size_t unmatched = 0;   // estimate poses with no reference within max_dt
};
PairedPoses pair_by_stamp(const common::Trajectory& estimate, const common::Trajectory& reference,
                          double max_dt = 0.02);

// The poses of a trajectory, without stamps.
common::PoseList poses_of(const common::Trajectory& trajectory);

}  // namespace ltm::eval
