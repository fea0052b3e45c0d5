#include "map/core/global_map.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "registration/core/voxel_hash.hpp"

namespace ltm::map {

std::optional<common::ConfigProblem> validate(const GlobalMapConfig& config) {
    GlobalMapConfig c = config;  // visit_fields takes a mutable config (loaders write through it)
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

common::PlyCloud build_global_map(const std::vector<PlacedLocalMap>& maps,
                                  const GlobalMapConfig& config, GlobalMapStats* stats) {
    double g = config.voxel_size;
    if (!(g > 0.0)) {
        g = 0.0;
        for (const PlacedLocalMap& m : maps) {
            if (m.map) g = std::max(g, double(m.map->voxel_size));
        }
    }
    GlobalMapBuilder builder(config, g);
    for (const PlacedLocalMap& m : maps) {
        if (m.map) builder.add(*m.map, m.T_world_anchor);
    }
    return builder.finish(stats);
}

GlobalMapBuilder::GlobalMapBuilder(const GlobalMapConfig& config, double grid)
    : config_(config), inv_(1.0 / (grid > 0.0 ? grid : 1.0)) {}

void GlobalMapBuilder::add(const common::LocalMapData& map,
                           const Eigen::Isometry3d& T_world_anchor) {
    const Eigen::Isometry3d T = T_world_anchor * map.T_anchor_grid;
    for (const common::VoxelData& v : map.voxels) {
        const bool has_normal = v.normal.allFinite() && v.normal.squaredNorm() > 0.5f;
        if (config_.with_normal_only && !has_normal) continue;
        if (double(v.planarity) < config_.min_planarity) continue;
        if (v.point_count < std::uint32_t(config_.min_point_count)) continue;
        if (!v.centre.allFinite()) continue;
        const Eigen::Vector3d p = T * v.centre.cast<double>();
        const Eigen::Vector3d q = (p * inv_).array().floor();
        if (!(q.cwiseAbs().maxCoeff() < double(registration::kVoxelKeyLimit))) continue;
        const registration::VoxelKey key =
            registration::pack_key(int(q.x()), int(q.y()), int(q.z()));
        const auto [it, inserted] = index_.emplace(key, cells_.size());
        if (inserted) cells_.emplace_back();
        Cell& c = cells_[it->second];
        const double w = std::max<double>(1.0, v.point_count);
        c.weight += w;
        c.sum += w * p;
        if (has_normal) {
            Eigen::Vector3d n = T.linear() * v.normal.cast<double>().normalized();
            if (!c.has_normal) {
                c.reference = n;
                c.has_normal = true;
            } else if (n.dot(c.reference) < 0.0) {
                n = -n;
            }
            c.normal_sum += w * n;
        }
        ++input_voxels_;
    }
}

common::PlyCloud GlobalMapBuilder::finish(GlobalMapStats* stats) const {
    common::PlyCloud out;
    out.points.reserve(cells_.size());
    out.normals.reserve(cells_.size());
    for (const Cell& c : cells_) {
        out.points.push_back((c.sum / c.weight).cast<float>());
        const double n = c.normal_sum.norm();
        out.normals.push_back(n > 1e-9 ? Eigen::Vector3f((c.normal_sum / n).cast<float>())
                                       : Eigen::Vector3f::Zero());
    }
    if (stats) {
        stats->input_voxels = input_voxels_;
        stats->fused_voxels = cells_.size();
    }
    return out;
}

}  // namespace ltm::map
