#include "odometry/core/local_map.hpp"

#include <cmath>

namespace ltm::odometry {

LocalMap::LocalMap(std::uint32_t id, const Eigen::Isometry3d& T_odom_anchor, double voxel_size,
                   double half_extent, const VoxelConfig& voxel_config, double stamp,
                   int coarse_factor)
    : id_(id),
      T_odom_anchor_(T_odom_anchor),
      half_extent_(half_extent),
      created_(stamp),
      last_update_(stamp),
      voxels_(voxel_size, voxel_config) {
    // Snapped to the coarsest lattice, so that both grids of all maps share their lattices.
    const double lattice = voxel_size * std::max(1, coarse_factor);
    const Eigen::Vector3d a = T_odom_anchor.translation();
    origin_ = (a / lattice).array().round().matrix() * lattice;
    box_centre_ = (a - origin_).cast<float>();
    if (coarse_factor >= 2) coarse_.emplace(voxel_size * coarse_factor, voxel_config);
}

Eigen::Isometry3d LocalMap::T_odom_map() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = origin_;
    return T;
}

std::size_t LocalMap::integrate(const std::vector<Eigen::Vector3f>& points,
                                const Eigen::Vector3f& sensor, double stamp) {
    auto inside = [this](const Eigen::Vector3f& p) { return contains(p); };
    const std::size_t absorbed = voxels_.integrate(points, sensor, stamp, inside);
    if (coarse_) coarse_->integrate(points, sensor, stamp, inside);
    if (absorbed > 0) {
        ++scans_;
        last_update_ = stamp;
    }
    return absorbed;
}

void LocalMap::seed_from(const LocalMap& other) {
    auto offset = [&](double size) -> Eigen::Vector3i {
        return ((other.origin_ - origin_) / size).array().round().cast<int>().matrix();
    };
    auto inside = [this](const Eigen::Vector3f& c) { return contains(c); };
    voxels_.seed_from(other.voxels_, offset(voxels_.voxel_size()), inside);
    if (coarse_ && other.coarse_) {
        coarse_->seed_from(*other.coarse_, offset(coarse_->voxel_size()), inside);
    }
}

std::size_t LocalMap::memory_bytes() const {
    return voxels_.memory_bytes() + (coarse_ ? coarse_->memory_bytes() : 0);
}

}  // namespace ltm::odometry
