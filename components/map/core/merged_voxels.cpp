#include "map/core/merged_voxels.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace ltm::map {
namespace {

bool usable(const common::VoxelData& v, const MergedVoxelsFilter& filter) {
    return v.point_count > 0 && v.planarity >= filter.min_planarity &&
           v.life.health >= filter.min_health && std::abs(v.normal.squaredNorm() - 1.0f) < 1e-3f &&
           v.centre.allFinite();
}

}  // namespace

MergedVoxels merge_voxels(const MapData& map, const MergedVoxelsFilter& filter) {
    std::unordered_map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const PoseGraphNode& n : map.nodes) anchors[n.id] = n.T_world_anchor;
    MergedVoxels out;
    out.voxels = std::make_shared<common::LocalMapData>();
    common::LocalMapData& merged = *out.voxels;
    float voxel_size = 0.0f;
    for (const StoredLocalMap& lm : map.local_maps) {
        if (lm.data && anchors.count(lm.node)) {
            voxel_size = std::max(voxel_size, lm.data->voxel_size);
        }
    }
    if (!(voxel_size > 0.0f)) voxel_size = 1.0f;
    merged.voxel_size = voxel_size;
    merged.finished = true;
    const float inv = 1.0f / voxel_size;
    std::unordered_map<std::uint64_t, std::uint32_t> slot;  // packed cell -> voxel index
    // Taking the voxel with the most points instead of the nearest anchor's made a patchwork of
    // local maps a few centimetres apart (a loop-closed map fitted its own scans with 85 % of the
    // structure within 0.3 m, against 99 % for a map from the true poses).
    std::vector<float> anchor_distance;  // per merged voxel
    std::vector<std::uint32_t> sessions;
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const StoredLocalMap& lm : map.local_maps) {
        const auto a = anchors.find(lm.node);
        if (!lm.data || a == anchors.end()) continue;
        ++out.local_maps;
        if (std::find(sessions.begin(), sessions.end(), lm.session) == sessions.end()) {
            sessions.push_back(lm.session);
        }
        const Eigen::Isometry3d T = a->second * lm.data->T_anchor_grid;
        const Eigen::Matrix3f R = T.linear().cast<float>();
        const Eigen::Vector3f t = T.translation().cast<float>();
        const Eigen::Vector3f anchor = a->second.translation().cast<float>();
        for (const common::VoxelData& v : lm.data->voxels) {
            if (!usable(v, filter)) continue;
            common::VoxelData w = v;
            w.centre = R * v.centre + t;
            w.normal = (R * v.normal).normalized();
            const Eigen::Vector3f cell = (w.centre * inv).array().floor();
            if (!(cell.cwiseAbs().maxCoeff() < float((1 << 20) - 1))) continue;
            w.index = cell.cast<int>();
            w.life.seen.clear();
            w.stability *= std::clamp(w.life.health, 0.0f, 1.0f);  // established voxels weigh more
            const std::uint64_t key = (std::uint64_t(w.index.x() + (1 << 20)) << 42) |
                                      (std::uint64_t(w.index.y() + (1 << 20)) << 21) |
                                      std::uint64_t(w.index.z() + (1 << 20));
            const float d = (w.centre - anchor).head<2>().norm();
            const auto [it, fresh] = slot.emplace(key, std::uint32_t(merged.voxels.size()));
            if (fresh) {
                merged.voxels.push_back(std::move(w));
                anchor_distance.push_back(d);
                lo = lo.cwiseMin(merged.voxels.back().centre.cast<double>());
                hi = hi.cwiseMax(merged.voxels.back().centre.cast<double>());
            } else if (d < anchor_distance[it->second]) {
                merged.voxels[it->second] = std::move(w);
                anchor_distance[it->second] = d;
            }
        }
    }
    out.sessions = sessions.size();
    merged.voxels.shrink_to_fit();  // kept for the session: no doubling slack (up to half)
    if (!merged.voxels.empty()) {
        merged.bbox_min = lo;
        merged.bbox_max = hi;
    }
    return out;
}

}  // namespace ltm::map
