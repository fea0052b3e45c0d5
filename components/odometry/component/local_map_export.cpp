#include "odometry/component/local_map_export.hpp"

#include <cmath>

namespace ltm::odometry {

common::LocalMapData export_local_map(const LocalMap& map, bool finished, std::uint32_t revision) {
    common::LocalMapData d;
    d.id = map.id();
    d.revision = revision;
    d.finished = finished;
    d.T_odom_anchor = map.T_odom_anchor();
    d.T_anchor_grid = map.T_odom_anchor().inverse() * map.T_odom_map();
    const Eigen::Vector3d anchor_in_grid = map.T_odom_anchor().translation() - map.origin();
    d.bbox_min = anchor_in_grid.array() - map.half_extent();
    d.bbox_max = anchor_in_grid.array() + map.half_extent();
    d.voxel_size = static_cast<float>(map.voxel_size());
    const VoxelGrid& grid = map.voxels();
    d.voxels.reserve(grid.size());
    for (std::size_t i = 0; i < grid.size(); ++i) {
        const Surfel& s = grid.surfels()[i];
        const VoxelRecord& r = grid.records()[i];
        common::VoxelData v;
        v.index = unpack_key(grid.keys()[i]);
        v.centre = s.centre;
        v.normal = s.normal;
        v.point_count = static_cast<std::uint32_t>(std::lround(r.sums.weight));
        v.planarity = s.planarity;
        v.stability = s.stability;
        v.life.created = r.created;
        v.life.last_seen = r.last_seen;
        v.life.observations = r.observations;
        d.voxels.push_back(std::move(v));
    }
    return d;
}

common::KeyframeData export_keyframe(const Keyframe& k, std::uint64_t scan_index,
                                     const Eigen::Isometry3d& T_odom_anchor) {
    common::KeyframeData d;
    d.id = k.id;
    d.scan_index = scan_index;
    d.local_map_id = k.local_map_id;
    d.stamp = k.stamp;
    d.T_odom_lidar = k.T_odom_lidar;
    d.T_anchor_lidar = T_odom_anchor.inverse() * k.T_odom_lidar;
    d.points = k.points;
    return d;
}

}  // namespace ltm::odometry
