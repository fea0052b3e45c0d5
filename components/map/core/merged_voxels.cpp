#include "map/core/merged_voxels.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace ltm::map {
bool merges(const common::VoxelData& v, const MergedVoxelsFilter& filter) {
    return v.point_count > 0 && v.planarity >= filter.min_planarity &&
           v.life.health >= filter.min_health && std::abs(v.normal.squaredNorm() - 1.0f) < 1e-3f &&
           v.centre.allFinite();
}

MergedVoxels merge_voxels(const MapData& map, const MergedVoxelsFilter& filter) {
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const PoseGraphNode& n : map.nodes) anchors[n.id] = n.T_world_anchor;
    float voxel_size = 0.0f;
    for (const StoredLocalMap& lm : map.local_maps) {
        if (lm.data && anchors.count(lm.node)) {
            voxel_size = std::max(voxel_size, lm.data->voxel_size);
        }
    }
    VoxelMerger merger(voxel_size, filter);
    for (const StoredLocalMap& lm : map.local_maps) {
        const auto a = anchors.find(lm.node);
        if (!lm.data || a == anchors.end()) continue;
        merger.add(lm, a->second);
    }
    return merger.finish();
}

VoxelMerger::VoxelMerger(float voxel_size, const MergedVoxelsFilter& filter) : filter_(filter) {
    if (!(voxel_size > 0.0f)) voxel_size = 1.0f;
    out_.voxels = std::make_shared<common::LocalMapData>();
    out_.voxels->voxel_size = voxel_size;
    out_.voxels->finished = true;
    inv_ = 1.0f / voxel_size;
}

void VoxelMerger::add(const StoredLocalMap& lm, const Eigen::Isometry3d& T_world_anchor) {
    if (!lm.data) return;
    common::LocalMapData& merged = *out_.voxels;
    ++out_.local_maps;
    if (std::find(sessions_.begin(), sessions_.end(), lm.session) == sessions_.end()) {
        sessions_.push_back(lm.session);
    }
    const Eigen::Isometry3d T = T_world_anchor * lm.data->T_anchor_grid;
    const Eigen::Matrix3f R = T.linear().cast<float>();
    const Eigen::Vector3f t = T.translation().cast<float>();
    const Eigen::Vector3f anchor = T_world_anchor.translation().cast<float>();
    const float inv = inv_;
    for (const common::VoxelData& v : lm.data->voxels) {
        if (!merges(v, filter_)) continue;
        const Eigen::Vector3f centre = R * v.centre + t;
        const Eigen::Vector3f cell = (centre * inv).array().floor();
        if (!(cell.cwiseAbs().maxCoeff() < float((1 << 20) - 1))) continue;
        const Eigen::Vector3i index = cell.cast<int>();
        const std::uint64_t key = (std::uint64_t(index.x() + (1 << 20)) << 42) |
                                  (std::uint64_t(index.y() + (1 << 20)) << 21) |
                                  std::uint64_t(index.z() + (1 << 20));
        const float d = (centre - anchor).head<2>().norm();
        bool fresh = false;
        std::uint32_t* const at = slot(key, &fresh);
        if (fresh) *at = std::uint32_t(merged.voxels.size());
        if (!fresh && !(d < anchor_distance_[*at])) continue;  // a nearer map's is kept
        // The voxel in the map frame; its life record keeps no observation indices (not copied).
        common::VoxelData w;
        w.index = index;
        w.centre = centre;
        w.normal = (R * v.normal).normalized();
        w.point_count = v.point_count;
        w.planarity = v.planarity;
        w.stability = v.stability * std::clamp(v.life.health, 0.0f, 1.0f);  // established: more
        w.life.created = v.life.created;
        w.life.last_seen = v.life.last_seen;
        w.life.observations = v.life.observations;
        w.life.health = v.life.health;
        if (fresh) {
            merged.voxels.push_back(std::move(w));
            anchor_distance_.push_back(d);
            lo_ = lo_.cwiseMin(merged.voxels.back().centre.cast<double>());
            hi_ = hi_.cwiseMax(merged.voxels.back().centre.cast<double>());
        } else {
            merged.voxels[*at] = std::move(w);
            anchor_distance_[*at] = d;
        }
    }
}

namespace {

constexpr std::uint64_t kEmptySlot = ~std::uint64_t(0);  // packed cells use 63 bits

std::size_t slot_hash(std::uint64_t key, std::size_t mask) {
    return std::size_t((key * 0x9E3779B97F4A7C15ull) >> 17) & mask;
}

}  // namespace

void VoxelMerger::grow() {
    std::vector<std::uint64_t> keys(std::max<std::size_t>(1024, 2 * slot_keys_.size()), kEmptySlot);
    std::vector<std::uint32_t> values(keys.size());
    const std::size_t mask = keys.size() - 1;
    for (std::size_t i = 0; i < slot_keys_.size(); ++i) {
        if (slot_keys_[i] == kEmptySlot) continue;
        std::size_t j = slot_hash(slot_keys_[i], mask);
        while (keys[j] != kEmptySlot) j = (j + 1) & mask;
        keys[j] = slot_keys_[i];
        values[j] = slot_values_[i];
    }
    slot_keys_ = std::move(keys);
    slot_values_ = std::move(values);
}

std::uint32_t* VoxelMerger::slot(std::uint64_t key, bool* fresh) {
    if (2 * (slot_count_ + 1) > slot_keys_.size()) grow();
    const std::size_t mask = slot_keys_.size() - 1;
    std::size_t j = slot_hash(key, mask);
    while (slot_keys_[j] != kEmptySlot) {
        if (slot_keys_[j] == key) {
            *fresh = false;
            return &slot_values_[j];
        }
        j = (j + 1) & mask;
    }
    slot_keys_[j] = key;
    ++slot_count_;
    *fresh = true;
    return &slot_values_[j];
}

MergedVoxels VoxelMerger::finish() {
    out_.sessions = sessions_.size();
    common::LocalMapData& merged = *out_.voxels;
    merged.voxels.shrink_to_fit();  // kept for the session: no doubling slack (up to half)
    if (!merged.voxels.empty()) {
        merged.bbox_min = lo_;
        merged.bbox_max = hi_;
    }
    slot_keys_ = {};
    slot_values_ = {};
    slot_count_ = 0;
    anchor_distance_ = {};
    return std::move(out_);
}

}  // namespace ltm::map
