#pragma once
// Simulated scans as binary PCD files (the layout of FAST-LIO style Scans/ folders), keeping
// per-point time: fields x y z intensity [t], float32, t in seconds after the scan stamp.
#include <string>

#include "common/core/point_cloud.hpp"

namespace ltm::sim::cli {

// Writes `cloud` to `path` as a binary PCD (v0.7): x y z intensity, plus t when the cloud has
// per-point time (intensity 0 when it has none). Throws common::IoError when it cannot write.
void write_scan_pcd(const std::string& path, const common::PointCloud& cloud);

}  // namespace ltm::sim::cli
