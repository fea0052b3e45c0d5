#include "odometry/core/local_map_export.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::odometry {

common::LocalMapData to_local_map_data(const LocalMap& map, std::uint32_t revision, bool finished,
                                       const std::vector<double>& observation_times) {
    common::LocalMapData d;
    const registration::VoxelGrid& grid = map.voxels();
    d.id = map.id();
    d.revision = revision;
    d.finished = finished;
    d.segment = map.segment();
    d.T_odom_anchor = map.T_odom_anchor();
    d.T_anchor_grid = map.T_odom_anchor().inverse() * map.T_odom_map();
    const Eigen::Vector3d centre = map.T_odom_anchor().translation() - map.origin();
    d.bbox_min = centre.array() - map.half_extent();
    d.bbox_max = centre.array() + map.half_extent();
    d.voxel_size = float(grid.voxel_size());
    d.observation_times = observation_times;
    d.voxels = grid.to_data();
    return d;
}

common::KeyframeData to_keyframe_data(const Keyframe& keyframe,
                                      const Eigen::Isometry3d& T_odom_anchor,
                                      std::uint64_t scan_index) {
    common::KeyframeData k;
    k.id = keyframe.id;
    k.scan_index = scan_index;
    k.local_map_id = keyframe.local_map_id;
    k.stamp = keyframe.stamp;
    k.T_odom_lidar = keyframe.T_odom_lidar;
    k.T_anchor_lidar = T_odom_anchor.inverse() * keyframe.T_odom_lidar;
    k.points = keyframe.points;
    return k;
}

}  // namespace ltm::odometry
