#pragma once
// Voxel centres in 8 m vertical columns (a 2-D hash of their x, y): the centres within a
// horizontal radius of a point without a scan of every voxel. Keeps a reference to the voxels,
// which must outlive it.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/core/local_map_data.hpp"

namespace ltm::localisation {

class VoxelColumns {
  public:
    static constexpr double kSize = 8.0;  // [m]

    explicit VoxelColumns(const std::vector<common::VoxelData>& voxels) : voxels_(voxels) {
        for (std::uint32_t i = 0; i < voxels.size(); ++i) {
            const Eigen::Vector3f& c = voxels[i].centre;
            cells_[key(c.x(), c.y())].push_back(i);
        }
    }

    // f(index) for every voxel whose centre is within `radius` (horizontal) of p, column by
    // column (x, then y, ascending), each column's in index order.
    template <class F>
    void for_each_near(const Eigen::Vector3d& p, double radius, F&& f) const {
        const double r2 = radius * radius;
        const int reach = int(std::ceil(radius / kSize));
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                const auto it = cells_.find(key(p.x() + dx * kSize, p.y() + dy * kSize));
                if (it == cells_.end()) continue;
                for (std::uint32_t i : it->second) {
                    const Eigen::Vector3f& c = voxels_[i].centre;
                    const double ex = c.x() - p.x(), ey = c.y() - p.y();
                    if (ex * ex + ey * ey <= r2) f(i);
                }
            }
        }
    }

    std::vector<Eigen::Vector3f> centres_near(const Eigen::Vector3d& p, double radius) const {
        std::vector<Eigen::Vector3f> out;
        for_each_near(p, radius, [&](std::uint32_t i) { out.push_back(voxels_[i].centre); });
        return out;
    }

  private:
    static std::uint64_t key(double x, double y) {
        const auto cx = std::int64_t(std::floor(x / kSize));
        const auto cy = std::int64_t(std::floor(y / kSize));
        return (std::uint64_t(cx + (1 << 30)) << 32) | std::uint64_t(cy + (1 << 30));
    }

    const std::vector<common::VoxelData>& voxels_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace ltm::localisation
