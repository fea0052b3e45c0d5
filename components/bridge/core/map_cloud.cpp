#include "bridge/core/map_cloud.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace ltm::bridge {
namespace {

struct Cell {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::uint32_t count = 0;
};

std::uint64_t cell_key(const Eigen::Vector3f& p, double inv_leaf) {
    // 21 bits a coordinate: +-1 million cells, +-500 km at 0.5 m.
    const auto c = [inv_leaf](float v) {
        return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v * inv_leaf)) +
                                          (1 << 20)) &
               0x1fffff;
    };
    return c(p.x()) | (c(p.y()) << 21) | (c(p.z()) << 42);
}

}  // namespace

std::vector<Eigen::Vector3f> decimate(const std::vector<Eigen::Vector3f>& points,
                                      std::size_t max_points, double& leaf_m) {
    std::unordered_map<std::uint64_t, Cell> cells;
    for (int attempt = 0; attempt < 64; ++attempt) {
        cells.clear();
        cells.reserve(std::min(points.size(), max_points * 2));
        const double inv_leaf = 1.0 / leaf_m;
        for (const Eigen::Vector3f& p : points) {
            if (!p.allFinite()) continue;
            Cell& c = cells[cell_key(p, inv_leaf)];
            c.sum += p.cast<double>();
            ++c.count;
        }
        if (cells.size() <= max_points) break;
        // Map surfaces are two-dimensional: the cells go with the square of the leaf.
        leaf_m *= std::max(
            1.1, 1.02 * std::sqrt(static_cast<double>(cells.size()) /
                                  static_cast<double>(std::max<std::size_t>(max_points, 1))));
    }
    std::vector<Eigen::Vector3f> out;
    out.reserve(cells.size());
    for (const auto& [key, c] : cells) out.push_back((c.sum / c.count).cast<float>());
    return out;
}

void MapCloud::set_local_map(std::uint64_t id, const Eigen::Isometry3d& T_odom_anchor,
                             std::vector<Eigen::Vector3f> points_anchor) {
    LocalMap& m = maps_[id];
    m.T_odom_anchor = T_odom_anchor;
    m.points = std::move(points_anchor);
    dirty_ = true;
}

void MapCloud::set_graph(std::map<std::uint64_t, Eigen::Isometry3d> T_map_anchor) {
    graph_ = std::move(T_map_anchor);
    dirty_ = true;
}

Eigen::Isometry3d MapCloud::map_from_odom() const {
    for (auto it = maps_.rbegin(); it != maps_.rend(); ++it) {
        const auto g = graph_.find(it->first);
        if (g != graph_.end()) return g->second * it->second.T_odom_anchor.inverse();
    }
    return Eigen::Isometry3d::Identity();
}

MapCloud::Cloud MapCloud::build() {
    dirty_ = false;
    Cloud cloud;
    cloud.in_map_frame = !graph_.empty();
    const Eigen::Isometry3d T_map_odom = map_from_odom();
    std::vector<Eigen::Vector3f> all;
    for (const auto& [id, m] : maps_) cloud.input_points += m.points.size();
    all.reserve(cloud.input_points);
    for (const auto& [id, m] : maps_) {
        Eigen::Isometry3d T = m.T_odom_anchor;
        if (cloud.in_map_frame) {
            const auto g = graph_.find(id);
            T = g != graph_.end() ? g->second : T_map_odom * m.T_odom_anchor;
        }
        const Eigen::Isometry3f Tf = T.cast<float>();
        for (const Eigen::Vector3f& p : m.points) all.push_back(Tf * p);
    }
    cloud.leaf_m = config_.leaf_m;
    cloud.points = decimate(all, config_.max_points, cloud.leaf_m);
    return cloud;
}

}  // namespace ltm::bridge
