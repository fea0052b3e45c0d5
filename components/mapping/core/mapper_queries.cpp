// The Mapper's queries: world poses of odometry frames and keyframes, the global map, the
// snapshot a save takes, memory (mapper.hpp; split from mapper.cpp, which adds and optimises).
#include <algorithm>
#include <cmath>

#include "map/core/global_map.hpp"
#include "mapping/core/mapper.hpp"

namespace ltm::mapping {

std::optional<Eigen::Isometry3d> Mapper::T_world_odom(std::uint64_t local_map_id) const {
    return T_world_odom(local_map_id, session_);
}

std::optional<Eigen::Isometry3d> Mapper::T_world_odom(std::uint64_t local_map_id,
                                                      std::uint32_t session) const {
    const std::optional<std::uint64_t> id = node_of(local_map_id, session);
    if (!id) return std::nullopt;
    const ChainAnchor a = chains_.anchor(view(), session, local_map_id, *id);
    return a.T_world_anchor * a.T_odom_anchor.inverse();
}

std::optional<Eigen::Isometry3d> Mapper::T_world_lidar(
    std::uint64_t local_map_id, const Eigen::Isometry3d& T_odom_lidar) const {
    return T_world_lidar(local_map_id, T_odom_lidar, session_);
}

std::optional<Eigen::Isometry3d> Mapper::T_world_lidar(std::uint64_t local_map_id,
                                                       const Eigen::Isometry3d& T_odom_lidar,
                                                       std::uint32_t session) const {
    const std::optional<Eigen::Isometry3d> c = T_world_odom(local_map_id, session);
    if (!c) return std::nullopt;
    return *c * T_odom_lidar;
}

Eigen::Isometry3d Mapper::keyframe_pose(std::uint32_t index) const {
    const map::StoredKeyframe& k = *keyframes_.at(index);
    return graph_.find(k.node)->T_world_anchor * k.data.T_anchor_lidar;
}

common::PlyCloud Mapper::global_map(map::GlobalMapStats* stats) const {
    std::map<std::uint64_t, const MapEntry*> ordered;
    for (const auto& [node, entry] : maps_) ordered[node] = &entry;
    double grid = config_.global_map.voxel_size;
    if (!(grid > 0.0)) {
        grid = 0.0;
        for (const auto& [node, entry] : ordered)
            grid = std::max(grid, double(meta(*entry).voxel_size));
    }
    // One at a time: a paged-out local map is read for it and let go (an unavailable one is
    // left out).
    map::GlobalMapBuilder builder(config_.global_map, grid);
    for (const auto& [node, entry] : ordered) {
        if (const std::shared_ptr<const common::LocalMapData> data = content(node, *entry))
            builder.add(*data, graph_.find(node)->T_world_anchor);
    }
    return builder.finish(stats);
}

map::MapData Mapper::snapshot() const {
    map::MapData m;
    m.revision = revision_;
    m.descriptor_config = config_.scan_context;
    m.localisation_descriptor_config = config_.localisation_descriptor;
    m.nodes = graph_.nodes();
    m.edges = graph_.edges();
    m.keyframes = keyframes_;
    std::map<std::uint64_t, const MapEntry*> ordered;
    for (const auto& [node, entry] : maps_) ordered[node] = &entry;
    for (const auto& [node, entry] : ordered) m.local_maps.push_back(entry->stored);
    m.sessions = sessions();
    return m;
}

std::size_t Mapper::memory_bytes() const { return memory().total(); }

Mapper::Memory Mapper::memory() const {
    Memory m;
    m.graph = graph_.nodes().capacity() * sizeof(map::PoseGraphNode) +
              graph_.edges().capacity() * sizeof(map::PoseGraphEdge) + folding_.memory_bytes() +
              chains_.memory_bytes();
    for (const auto& [node, entry] : maps_) {
        if (!entry.stored.data) {  // paged out
            m.local_maps += sizeof(common::LocalMapData) + sizeof(map::LocalMapFile);
            continue;
        }
        const common::LocalMapData& d = *entry.stored.data;
        m.local_maps += sizeof(common::LocalMapData) +
                        d.voxels.capacity() * sizeof(common::VoxelData) +
                        d.observation_times.capacity() * sizeof(double);
        for (const common::VoxelData& v : d.voxels)
            m.local_maps += v.life.seen.capacity() * sizeof(std::uint16_t);
    }
    for (const auto& k : keyframes_) {
        m.keyframes += sizeof(map::StoredKeyframe) + k->descriptor.memory_bytes() +
                       k->localisation_descriptor.memory_bytes() +
                       k->data.points.capacity() * sizeof(Eigen::Vector3f);
    }
    m.loop_targets = verifier_.memory_bytes();
    m.removed_cells = removed_.memory_bytes();
    return m;
}

}  // namespace ltm::mapping
