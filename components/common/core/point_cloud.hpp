#pragma once
// The core point-cloud type shared by every ltm library. No middleware in here.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace ltm::common {

struct PointCloud {
    std::vector<Eigen::Vector3f> points;  // sensor frame [m]
    std::vector<float> intensity;         // empty, or one per point
    std::vector<float> time;              // empty, or per point: seconds after `stamp`
    double stamp = 0.0;                   // acquisition time of the scan [s]
    std::string frame_id = "lidar";

    std::size_t size() const { return points.size(); }
    bool empty() const { return points.empty(); }
    bool has_intensity() const { return !intensity.empty(); }
    bool has_time() const { return !time.empty(); }
    void reserve(std::size_t n, bool with_intensity, bool with_time);
    void clear();
    // True when every optional channel is empty or has one value per point.
    bool consistent() const;
};

// Drops NaN and infinite points in place (with their channels); returns how many were dropped.
std::size_t remove_non_finite(PointCloud& cloud);

}  // namespace ltm::common
