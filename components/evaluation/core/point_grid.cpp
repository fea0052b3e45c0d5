#include "evaluation/core/point_grid.hpp"

#include <cmath>

namespace ltm::eval {

PointGrid::PointGrid(const std::vector<Eigen::Vector3f>& points, double radius)
    : radius_(radius > 0.0 ? radius : 1e-3), points_(points) {
    cells_.reserve(points_.size() / 4 + 1);
    for (std::uint32_t i = 0; i < points_.size(); ++i)
        if (points_[i].allFinite()) cells_[key(cell(points_[i]))].push_back(i);
}

Eigen::Vector3i PointGrid::cell(const Eigen::Vector3f& p) const {
    return (p.cast<double>() / radius_).array().floor().cast<int>();
}

std::int64_t PointGrid::key(const Eigen::Vector3i& c) const {
    // 21 bits a coordinate: +-1e6 cells, i.e. +-1000 km at 1 mm cells.
    const auto u = [](int v) { return static_cast<std::int64_t>(v + (1 << 20)) & 0x1FFFFF; };
    return (u(c.x()) << 42) | (u(c.y()) << 21) | u(c.z());
}

double PointGrid::nearest_within(const Eigen::Vector3f& q) const {
    if (!q.allFinite()) return -1.0;
    const Eigen::Vector3i c = cell(q);
    const double r2 = radius_ * radius_;
    double best = -1.0;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                const auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
                if (it == cells_.end()) continue;
                for (std::uint32_t i : it->second) {
                    const double d2 = (points_[i] - q).cast<double>().squaredNorm();
                    if (d2 <= r2 && (best < 0.0 || d2 < best)) best = d2;
                }
            }
    return best < 0.0 ? -1.0 : std::sqrt(best);
}

bool PointGrid::has_neighbour(const Eigen::Vector3f& q) const { return nearest_within(q) >= 0.0; }

}  // namespace ltm::eval
