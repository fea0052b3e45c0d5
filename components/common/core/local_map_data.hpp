#pragma once
// The plain data of a local map and of a keyframe, as they travel between odometry, mapping,
// map files, localisation and maintenance (mirrors ltm_msgs/LocalMap and ltm_msgs/Keyframe).
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

namespace ltm::common {

// Life record of a voxel (METHOD.md section 5).
struct VoxelLife {
    double created = 0.0;             // stamp of the first observation [s]
    double last_seen = 0.0;           // stamp of the last observation [s]
    std::uint32_t observations = 0;   // scans that hit the voxel
    float health = 1.0f;              // 0..1
    std::vector<std::uint16_t> seen;  // indices into LocalMapData::observation_times (may be empty)
};

struct VoxelData {
    Eigen::Vector3i index = Eigen::Vector3i::Zero();   // lattice cell: floor(p_grid / voxel_size)
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // mean of the points, grid frame [m]
    Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit; zero when the voxel has none yet
    std::uint32_t point_count = 0;
    float planarity = 0.0f;  // 0..1
    float stability = 0.0f;  // |n_old . n_new| (Eq. 7)
    VoxelLife life;
};

// M_k = {T_k, B_k, V_k} (Eq. 9). Voxels are on a lattice (the grid frame) fixed to the anchor:
// p_odom = T_odom_anchor * T_anchor_grid * p_grid, so moving an anchor moves its voxels.
struct LocalMapData {
    std::uint64_t id = 0;
    std::uint32_t revision = 0;  // increases with every snapshot of the same map
    bool finished = false;       // false: a snapshot of a map still being built
    // Odometry segment: increases each time the odometry lost track and restarted at its best
    // estimate. Maps of one segment are joined by odometry; the first map of a new segment has
    // no reliable odometry relation to the maps before it (a loop or localisation joins them).
    std::uint32_t segment = 0;
    Eigen::Isometry3d T_odom_anchor = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_anchor_grid = Eigen::Isometry3d::Identity();
    Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();  // grid frame [m]
    Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
    float voxel_size = 1.0f;                // [m]
    std::vector<double> observation_times;  // stamps of the scans that updated it [s]
    std::vector<VoxelData> voxels;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// A registered scan kept for loop closure and re-localisation.
struct KeyframeData {
    std::uint64_t id = 0;
    std::uint64_t scan_index = 0;  // index of the scan in its input stream
    std::uint64_t local_map_id = 0;
    // Odometry segment of that local map (LocalMapData::segment), when the sender knew it: a
    // keyframe can arrive long before its local map does (a map crosses a link when finished).
    std::optional<std::uint32_t> segment;
    double stamp = 0.0;  // [s]
    Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_anchor_lidar = Eigen::Isometry3d::Identity();
    std::vector<Eigen::Vector3f> points;  // down-sampled, LiDAR frame
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace ltm::common
