#include "bridge/core/map_cloud.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::bridge {
namespace {

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

std::vector<Eigen::Vector3f> VoxelDecimator::decimate(const std::vector<Eigen::Vector3f>& points,
                                                      std::size_t max_points, double& leaf_m) {
    // Open addressing (linear probing) over a table kept between calls: a map cloud of 600 000
    // points goes through it in milliseconds, where std::unordered_map allocates a node a cell.
    std::size_t capacity = 1024;
    while (capacity < 2 * max_points + 2) capacity *= 2;
    if (cells_.size() != capacity) cells_.assign(capacity, Cell{});
    const std::size_t mask = capacity - 1;
    std::vector<std::size_t> used;
    used.reserve(max_points + 1);
    for (int attempt = 0; attempt < 64; ++attempt) {
        for (const std::size_t i : used) cells_[i] = Cell{};
        used.clear();
        const double inv_leaf = 1.0 / leaf_m;
        std::size_t done = 0;
        bool overflow = false;
        for (const Eigen::Vector3f& p : points) {
            if (!p.allFinite()) {
                ++done;
                continue;
            }
            const std::uint64_t key = cell_key(p, inv_leaf) + 1;  // 0: an empty slot
            std::size_t i = (key * 0x9E3779B97F4A7C15ull) >> 20 & mask;
            while (cells_[i].key != 0 && cells_[i].key != key) i = (i + 1) & mask;
            Cell& c = cells_[i];
            if (c.key == 0) {
                if (used.size() == max_points) {  // one cell too many: a coarser leaf
                    overflow = true;
                    break;
                }
                c.key = key;
                used.push_back(i);
            }
            c.sum += p.cast<double>();
            ++c.count;
            ++done;
        }
        if (!overflow) break;
        // Map surfaces are two-dimensional: the cells go with the square of the leaf. The cells
        // a full pass would make, from the share of the points this one took, overestimates
        // (the first points find new cells more often than the later), so the leaf grows by at
        // most a quarter a pass (a pass that overflows stops early: it costs max_points cells).
        const double expected = static_cast<double>(used.size()) *
                                static_cast<double>(points.size()) /
                                static_cast<double>(std::max<std::size_t>(done, 1));
        const double ratio = expected / static_cast<double>(std::max<std::size_t>(max_points, 1));
        leaf_m *= std::clamp(1.02 * std::sqrt(ratio), 1.05, 1.25);
    }
    std::vector<Eigen::Vector3f> out;
    out.reserve(used.size());
    for (const std::size_t i : used) out.push_back((cells_[i].sum / cells_[i].count).cast<float>());
    for (const std::size_t i : used) cells_[i] = Cell{};  // empty for the next call
    return out;
}

std::vector<Eigen::Vector3f> decimate(const std::vector<Eigen::Vector3f>& points,
                                      std::size_t max_points, double& leaf_m) {
    VoxelDecimator d;
    return d.decimate(points, max_points, leaf_m);
}

void MapCloud::set_local_map(std::uint64_t id, const Eigen::Isometry3d& T_odom_anchor,
                             std::vector<Eigen::Vector3f> points_anchor) {
    LocalMap& m = maps_[id];
    kept_ -= m.points.size();
    m.T_odom_anchor = T_odom_anchor;
    if (kept_leaf_ > 0.0) {
        double leaf = kept_leaf_;  // never coarser: max_points is its point count
        points_anchor =
            decimate(points_anchor, std::max<std::size_t>(points_anchor.size(), 1), leaf);
    }
    m.points = std::move(points_anchor);
    m.points.shrink_to_fit();
    kept_ += m.points.size();
    dirty_ = true;
    bound();
}

void MapCloud::bound() {
    const std::size_t cap = config_.max_kept_points > 0
                                ? config_.max_kept_points
                                : 4 * std::max<std::size_t>(config_.max_points, 1);
    // (a leaf past 10 km keeps one point a map: nothing coarser helps)
    while (kept_ > cap && kept_leaf_ < 1e4) {
        kept_leaf_ = kept_leaf_ > 0.0 ? 1.25 * kept_leaf_ : config_.leaf_m;
        kept_ = 0;
        for (auto& [id, m] : maps_) {
            double leaf = kept_leaf_;
            m.points = decimate(m.points, std::max<std::size_t>(m.points.size(), 1), leaf);
            m.points.shrink_to_fit();
            kept_ += m.points.size();
        }
    }
}

std::size_t MapCloud::memory_bytes() const {
    std::size_t n = 0;
    for (const auto& [id, m] : maps_)
        n += sizeof(LocalMap) + m.points.capacity() * sizeof(Eigen::Vector3f);
    return n;
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
    cloud.points = decimator_.decimate(all, config_.max_points, cloud.leaf_m);
    return cloud;
}

}  // namespace ltm::bridge
