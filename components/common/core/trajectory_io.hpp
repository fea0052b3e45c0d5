#pragma once
// Trajectory files: KITTI (3x4 row-major a line) and TUM (t x y z qx qy qz qw a line).
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace ltm::common {

using PoseList = std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>;

struct StampedPose {
    double stamp = 0.0;  // [s]
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};
using Trajectory = std::vector<StampedPose, Eigen::aligned_allocator<StampedPose>>;

// Throws IoError naming the line of a malformed entry.
PoseList read_kitti_poses(const std::string& path);
void write_kitti_poses(const std::string& path, const PoseList& poses);
Trajectory read_tum_trajectory(const std::string& path);
void write_tum_trajectory(const std::string& path, const Trajectory& trajectory);

// One line of each format, for streaming writers.
std::string format_kitti_pose(const Eigen::Isometry3d& pose);
std::string format_tum_pose(double stamp, const Eigen::Isometry3d& pose);

// Camera-frame poses (KITTI ground truth) to LiDAR-frame poses: Tr^-1 * P_cam * Tr.
PoseList camera_to_lidar_poses(const PoseList& camera_poses, const Eigen::Isometry3d& Tr);

}  // namespace ltm::common
