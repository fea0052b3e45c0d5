#include "mapping/core/drift_distance.hpp"

#include <limits>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

namespace ltm::mapping {

double drift_distance(const PoseGraph& graph, std::uint64_t from, std::uint64_t to,
                      const std::function<double(const map::PoseGraphEdge&)>& odometry_length) {
    if (from == to) return 0.0;
    std::unordered_map<std::uint64_t, std::vector<std::pair<std::uint64_t, double>>> adjacent;
    for (const map::PoseGraphEdge& e : graph.edges()) {
        if (!e.active) continue;
        const double w = e.kind == map::EdgeKind::kLoop ? 0.0 : std::max(0.0, odometry_length(e));
        if (!(w < std::numeric_limits<double>::infinity())) continue;  // bounds nothing
        adjacent[e.from].push_back({e.to, w});
        adjacent[e.to].push_back({e.from, w});
    }
    // Dijkstra from `from` until `to` is settled.
    using Item = std::pair<double, std::uint64_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    std::unordered_map<std::uint64_t, double> best;
    best[from] = 0.0;
    open.push({0.0, from});
    while (!open.empty()) {
        const auto [d, node] = open.top();
        open.pop();
        if (node == to) return d;
        if (d > best[node]) continue;
        const auto it = adjacent.find(node);
        if (it == adjacent.end()) continue;
        for (const auto& [next, w] : it->second) {
            const auto b = best.find(next);
            if (b != best.end() && b->second <= d + w) continue;
            best[next] = d + w;
            open.push({d + w, next});
        }
    }
    return std::numeric_limits<double>::infinity();
}

}  // namespace ltm::mapping
