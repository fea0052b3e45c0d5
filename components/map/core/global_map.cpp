#include "map/core/global_map.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "registration/core/voxel_hash.hpp"

namespace ltm::map {
namespace {

struct Cell {
    double weight = 0.0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d reference = Eigen::Vector3d::Zero();  // first normal: sign reference
    bool has_normal = false;
};

}  // namespace

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
        if (!(g > 0.0)) g = 1.0;
    }
    const double inv = 1.0 / g;
    std::unordered_map<registration::VoxelKey, std::size_t> index;
    std::vector<Cell> cells;
    GlobalMapStats st;
    for (const PlacedLocalMap& m : maps) {
        if (!m.map) continue;
        const Eigen::Isometry3d T = m.T_world_anchor * m.map->T_anchor_grid;
        for (const common::VoxelData& v : m.map->voxels) {
            const bool has_normal = v.normal.allFinite() && v.normal.squaredNorm() > 0.5f;
            if (config.with_normal_only && !has_normal) continue;
            if (double(v.planarity) < config.min_planarity) continue;
            if (v.point_count < std::uint32_t(config.min_point_count)) continue;
            if (!v.centre.allFinite()) continue;
            const Eigen::Vector3d p = T * v.centre.cast<double>();
            const Eigen::Vector3d q = (p * inv).array().floor();
            if (!(q.cwiseAbs().maxCoeff() < double(registration::kVoxelKeyLimit))) continue;
            const registration::VoxelKey key =
                registration::pack_key(int(q.x()), int(q.y()), int(q.z()));
            const auto [it, inserted] = index.emplace(key, cells.size());
            if (inserted) cells.emplace_back();
            Cell& c = cells[it->second];
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
            ++st.input_voxels;
        }
    }
    common::PlyCloud out;
    out.points.reserve(cells.size());
    out.normals.reserve(cells.size());
    for (const Cell& c : cells) {
        out.points.push_back((c.sum / c.weight).cast<float>());
        const double n = c.normal_sum.norm();
        out.normals.push_back(n > 1e-9 ? Eigen::Vector3f((c.normal_sum / n).cast<float>())
                                       : Eigen::Vector3f::Zero());
    }
    st.fused_voxels = cells.size();
    if (stats) *stats = st;
    return out;
}

}  // namespace ltm::map
