#pragma once
// One voxel of a local map (Eq. 2, 7): running sums giving its centre and normal in O(1), the
// previous normal, planarity, stability s = |n_old . n_new| and the life record (section 5).
#include <Eigen/Core>
#include <cstdint>

#include "registration/core/registration_config.hpp"

namespace ltm::registration {

// Running sums of a voxel's points, relative to the centre of its grid cell (small numbers, so
// float keeps the covariance accurate).
struct VoxelSums {
    float weight = 0.0f;                            // points absorbed (scaled past max_points)
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();  // sum of q
    Eigen::Matrix<float, 6, 1> sum_sq =             // sum of q q^T: xx xy xz yy yz zz
        Eigen::Matrix<float, 6, 1>::Zero();

    void add(const Eigen::Vector3f& q) {
        weight += 1.0f;
        sum += q;
        sum_sq += Eigen::Matrix<float, 6, 1>(q.x() * q.x(), q.x() * q.y(), q.x() * q.z(),
                                             q.y() * q.y(), q.y() * q.z(), q.z() * q.z());
    }
    void scale(float f) {
        weight *= f;
        sum *= f;
        sum_sq *= f;
    }
    Eigen::Vector3f mean() const { return sum / weight; }
    Eigen::Matrix3d covariance() const;
};

// What registration reads of a voxel (hot data, 36 bytes).
struct Surfel {
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // mean of the points, map frame [m]
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit, smallest eigenvector; 0: none yet
    float stability = 0.0f;                            // s = |n_old . n_new| (Eq. 7) [0..1]
    float planarity = 0.0f;                            // 1 - l_min / l_mid [0..1]
    std::uint32_t usable = 0;                          // has a normal on a plane-like voxel
};

// Cold data of a voxel: the sums, the previous normal and the life record.
struct VoxelRecord {
    VoxelSums sums;
    Eigen::Vector3f previous_normal = Eigen::Vector3f::Zero();  // n_old of the last update, or 0
    double created = 0.0;            // stamp of the first scan that hit it [s]
    double last_seen = 0.0;          // stamp of the last scan that hit it [s]
    std::uint32_t observations = 0;  // scans that hit it
    std::uint32_t last_scan = 0;     // internal: integration pass that last touched it
};

// Recomputes the surfel from the sums after a scan was absorbed (Eq. 2, 7): centre, normal
// (oriented like the previous normal, or towards `sensor` the first time), planarity,
// stability. `cell_centre` is where the sums are relative to (map frame). Usable: enough points,
// planarity >= min_planarity and sqrt(l_mid) >= min_extent * voxel_size.
void update_surfel(const VoxelConfig& config, float voxel_size, const Eigen::Vector3f& cell_centre,
                   const Eigen::Vector3f& sensor, VoxelRecord& record, Surfel& surfel);

}  // namespace ltm::registration
