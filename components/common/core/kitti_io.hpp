#pragma once
// KITTI odometry layout: velodyne/NNNNNN.bin (float32 x y z intensity), times.txt, calib.txt.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"

namespace ltm::common {

// Reads one .bin scan. Throws IoError on a missing, unreadable or truncated file.
PointCloud read_kitti_bin(const std::string& path);
// Writes x y z intensity float32 (intensity 0 when the cloud has none).
void write_kitti_bin(const std::string& path, const PointCloud& cloud);

// The sorted .bin files of a KITTI-layout folder: DIR/velodyne/*.bin, or DIR/*.bin.
std::vector<std::string> list_kitti_scans(const std::string& dir);
// The folder holding times.txt / calib.txt / poses.txt for a scan folder (DIR or DIR/..).
std::string kitti_sequence_dir(const std::string& dir);

// One time [s] a line. Throws IoError naming the line of a malformed value.
std::vector<double> read_times(const std::string& path);
void write_times(const std::string& path, const std::vector<double>& times);

// `Tr` of a KITTI calib.txt: T_camera_lidar. Identity when the file has no Tr line.
Eigen::Isometry3d read_kitti_calib_tr(const std::string& path);

}  // namespace ltm::common
