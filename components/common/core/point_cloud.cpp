#include "common/core/point_cloud.hpp"

namespace ltm::common {

void PointCloud::reserve(std::size_t n, bool with_intensity, bool with_time) {
    points.reserve(n);
    if (with_intensity) intensity.reserve(n);
    if (with_time) time.reserve(n);
}

void PointCloud::clear() {
    points.clear();
    intensity.clear();
    time.clear();
}

bool PointCloud::consistent() const {
    return (intensity.empty() || intensity.size() == points.size()) &&
           (time.empty() || time.size() == points.size());
}

std::size_t remove_non_finite(PointCloud& cloud) {
    std::size_t out = 0;
    const std::size_t n = cloud.points.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (!cloud.points[i].allFinite()) continue;
        if (out != i) {
            cloud.points[out] = cloud.points[i];
            if (!cloud.intensity.empty()) cloud.intensity[out] = cloud.intensity[i];
            if (!cloud.time.empty()) cloud.time[out] = cloud.time[i];
        }
        ++out;
    }
    cloud.points.resize(out);
    if (!cloud.intensity.empty()) cloud.intensity.resize(out);
    if (!cloud.time.empty()) cloud.time.resize(out);
    return n - out;
}

}  // namespace ltm::common
