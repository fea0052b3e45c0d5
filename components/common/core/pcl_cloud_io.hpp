#pragma once
// PCD and PLY point-cloud files, read through PCL (kept out of every other translation unit).
#include <string>

#include "common/core/point_cloud.hpp"

namespace ltm::common {

// Reads x y z (float32 or float64) and, when present, intensity from a .pcd or .ply file.
// Throws IoError with one line naming the file and the problem (missing, malformed, no x y z).
PointCloud load_cloud_file(const std::string& path);

// True for the extensions load_cloud_file reads (.pcd, .ply).
bool is_cloud_file(const std::string& path);

}  // namespace ltm::common
