#pragma once
// PCD and PLY point-cloud files, read through PCL (kept out of every other translation unit).
#include <string>

#include "common/core/point_cloud.hpp"

namespace ltm::common {

// Reads x y z (float32 or float64) and, when present, intensity from a .pcd or .ply file, and
// per-point time from a field t, time, timestamp or offset_time (float32 x y z): floating fields
// in seconds, integer fields in nanoseconds (Ouster `t`, Livox `offset_time`), values over 1e6 s
// taken as absolute and made relative to `stamp` (the scan's stamp [s]).
// Throws IoError with one line naming the file and the problem (missing, malformed, no x y z).
PointCloud load_cloud_file(const std::string& path, double stamp = 0.0);

// True for the extensions load_cloud_file reads (.pcd, .ply).
bool is_cloud_file(const std::string& path);

}  // namespace ltm::common
