#include "runtime/convert/local_map.hpp"

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {
namespace {

Eigen::Vector3d to_vec(const msg::Point& p) { return {p.x, p.y, p.z}; }
msg::Point to_point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

common::LocalMapData from_msg(const msg::LocalMap& m) {
    common::LocalMapData d;
    d.id = m.id;
    d.revision = m.revision;
    d.finished = m.finished;
    d.segment = m.segment;
    d.T_odom_anchor = to_isometry(m.anchor);
    d.T_anchor_grid = to_isometry(m.grid_in_anchor);
    d.bbox_min = to_vec(m.bbox_min);
    d.bbox_max = to_vec(m.bbox_max);
    d.voxel_size = m.voxel_size;
    d.observation_times = to_vector(m.observation_times);
    d.voxels.resize(m.voxels._length);
    for (std::uint32_t i = 0; i < m.voxels._length; ++i) {
        const msg::Voxel& v = m.voxels._buffer[i];
        common::VoxelData& o = d.voxels[i];
        o.index = {v.ix, v.iy, v.iz};
        o.centre = {v.centre[0], v.centre[1], v.centre[2]};
        o.normal = {v.normal[0], v.normal[1], v.normal[2]};
        o.point_count = v.point_count;
        o.planarity = v.planarity;
        o.stability = v.stability;
        o.life.created = v.life.created;
        o.life.last_seen = v.life.last_seen;
        o.life.observations = v.life.observations;
        o.life.health = v.life.health;
        o.life.seen = to_vector(v.life.seen);
    }
    return d;
}

common::KeyframeData from_msg(const msg::Keyframe& m) {
    common::KeyframeData k;
    k.id = m.id;
    k.scan_index = m.scan_index;
    k.local_map_id = m.local_map_id;
    k.segment = m.segment;
    k.stamp = to_seconds(m.header.stamp);
    k.T_odom_lidar = to_isometry(m.pose);
    k.T_anchor_lidar = to_isometry(m.pose_in_anchor);
    common::PointCloud cloud;
    if (from_pointcloud2(m.points, cloud).empty()) k.points = std::move(cloud.points);
    return k;
}

const msg::LocalMap& LocalMapBuilder::build(const common::LocalMapData& d, double stamp,
                                            const std::string& frame_id) {
    voxels_.resize(d.voxels.size());
    for (std::size_t i = 0; i < d.voxels.size(); ++i) {
        const common::VoxelData& v = d.voxels[i];
        msg::Voxel& o = voxels_[i];
        o = msg::Voxel{};
        o.ix = v.index.x();
        o.iy = v.index.y();
        o.iz = v.index.z();
        for (int k = 0; k < 3; ++k) {
            o.centre[k] = v.centre[k];
            o.normal[k] = v.normal[k];
        }
        o.point_count = v.point_count;
        o.planarity = v.planarity;
        o.stability = v.stability;
        o.life.created = v.life.created;
        o.life.last_seen = v.life.last_seen;
        o.life.observations = v.life.observations;
        o.life.health = v.life.health;
        borrow_sequence(o.life.seen, v.life.seen);
    }
    frame_id_ = frame_id;
    message_ = msg::LocalMap{};
    message_.header.stamp = to_time(stamp);
    message_.header.frame_id = borrow_string(frame_id_);
    message_.id = d.id;
    message_.revision = d.revision;
    message_.finished = d.finished;
    message_.segment = d.segment;
    message_.anchor = to_pose(d.T_odom_anchor);
    message_.grid_in_anchor = to_pose(d.T_anchor_grid);
    message_.bbox_min = to_point(d.bbox_min);
    message_.bbox_max = to_point(d.bbox_max);
    message_.voxel_size = d.voxel_size;
    borrow_sequence(message_.observation_times, d.observation_times);
    borrow_sequence(message_.voxels, voxels_);
    return message_;
}

const msg::Keyframe& KeyframeBuilder::build(const common::KeyframeData& k,
                                            const std::string& frame_id,
                                            const std::string& lidar_frame_id) {
    cloud_.clear();
    cloud_.points = k.points;
    cloud_.stamp = k.stamp;
    cloud_.frame_id = lidar_frame_id;
    frame_id_ = frame_id;
    message_ = msg::Keyframe{};
    message_.header.stamp = to_time(k.stamp);
    message_.header.frame_id = borrow_string(frame_id_);
    message_.id = k.id;
    message_.scan_index = k.scan_index;
    message_.local_map_id = k.local_map_id;
    message_.segment = k.segment.value_or(0);
    message_.pose = to_pose(k.T_odom_lidar);
    message_.pose_in_anchor = to_pose(k.T_anchor_lidar);
    message_.points = points_.build(cloud_);
    return message_;
}

}  // namespace ltm::convert
