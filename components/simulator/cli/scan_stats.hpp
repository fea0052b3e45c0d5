#pragma once
// Statistics that show how LiDAR-like a scan is, computed the same way for real KITTI scans and
// simulated ones: points a scan, points per ring, elevation per ring, ranges, intensities.
#include <cstddef>
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"

namespace ltm::sim::cli {

// Ring of every point of a KITTI-ordered scan (ring by ring from the top, each ring turning
// counter-clockwise from the front): a new ring starts where the azimuth steps from the fourth
// quadrant into the first. The usual way to recover rings from KITTI .bin files.
std::vector<int> rings_from_order(const common::PointCloud& cloud);

struct ScanStats {
    std::size_t points = 0;
    std::vector<double> ring_points;     // points per ring (averaged when accumulated)
    std::vector<double> ring_elevation;  // median elevation per ring [deg]
    std::vector<double> range_edges;     // histogram bin edges [m]
    std::vector<double> range_fraction;  // share of points per bin
    std::vector<double> intensity_pct;   // 10, 25, 50, 75, 90 % percentiles
    double range_median = 0.0;
};

// Stats of one scan; `range_edges` defines the histogram (last bin open-ended).
ScanStats scan_stats(const common::PointCloud& cloud, const std::vector<double>& range_edges);
// Mean of several scans' stats (rings aligned by index).
ScanStats average_stats(const std::vector<ScanStats>& stats);
// A side-by-side text table, one column per set of scans (the first is the reference).
std::string compare_table(const std::vector<ScanStats>& columns,
                          const std::vector<std::string>& names);

}  // namespace ltm::sim::cli
