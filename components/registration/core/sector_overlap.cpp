#include "registration/core/sector_overlap.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::registration {

SectorCounter::SectorCounter(int sectors)
    : width_(2.0 * M_PI / double(std::max(sectors, 1))),
      points_(std::size_t(std::max(sectors, 1)), 0),
      explained_(points_.size(), 0) {}

void SectorCounter::add(const Eigen::Vector3f& p, bool explained) {
    // Sector 0 centred on the x axis.
    double azimuth = std::atan2(double(p.y()), double(p.x())) + 0.5 * width_;
    if (azimuth < 0.0) azimuth += 2.0 * M_PI;
    const std::size_t s =
        std::min(std::size_t(std::max(std::floor(azimuth / width_), 0.0)), points_.size() - 1);
    ++total_;
    ++points_[s];
    explained_[s] += explained;
}

SectorOverlap SectorCounter::weakest(double min_share) const {
    SectorOverlap out;
    for (std::size_t s = 0; s < points_.size(); ++s) {
        if (points_[s] == 0 || double(points_[s]) < min_share * double(total_)) continue;
        const double f = double(explained_[s]) / double(points_[s]);
        if (f < out.min_fraction) {
            out.min_fraction = f;
            out.weakest_deg = double(s) * width_ * 180.0 / M_PI;
        }
    }
    return out;
}

SectorOverlap sector_overlap(const std::vector<Eigen::Vector3f>& points, const VoxelGrid& grid,
                             const Eigen::Isometry3d& T_grid_lidar, const ImlsParams& imls,
                             double inlier_distance, int sectors, double min_share) {
    SectorCounter counter(sectors);
    const Eigen::Matrix3f R = T_grid_lidar.linear().cast<float>();
    const Eigen::Vector3f t = T_grid_lidar.translation().cast<float>();
    ImlsResult r;
    for (const Eigen::Vector3f& p : points) {
        const bool explained =
            imls_distance(grid, R * p + t, imls, &r) && std::abs(r.distance) <= inlier_distance;
        counter.add(p, explained);
    }
    return counter.weakest(min_share);
}

}  // namespace ltm::registration
