#include "mapping/core/long_term_folding.hpp"

#include <limits>
#include <vector>

namespace ltm::mapping {

const LongTermFolding::Folded* LongTermFolding::find(std::uint32_t session,
                                                     std::uint64_t local_map_id) const {
    const auto s = folded_.find(session);
    if (s == folded_.end()) return nullptr;
    const auto it = s->second.find(local_map_id);
    return it == s->second.end() ? nullptr : &it->second;
}

void LongTermFolding::record(std::uint32_t session, std::uint64_t local_map_id,
                             const Folded& folded) {
    folded_[session][local_map_id] = folded;
}

PoseGraph LongTermFolding::without(const PoseGraph& graph, std::uint64_t n, std::uint64_t into,
                                   const Eigen::Isometry3d& T_into_n,
                                   int max_loops_per_anchor_pair) {
    const Eigen::Isometry3d T_n_into = T_into_n.inverse();
    PoseGraph updated(graph.config());
    for (const map::PoseGraphNode& x : graph.nodes()) {
        if (x.id != n) updated.add_node(x);
    }
    std::vector<map::PoseGraphEdge> moved;
    for (const map::PoseGraphEdge& x : graph.edges()) {
        if (x.from != n && x.to != n) {
            updated.add_edge(x);
            continue;
        }
        map::PoseGraphEdge y = x;
        if (y.from == n) {
            y.from = into;
            y.T_from_to = T_into_n * y.T_from_to;
        }
        if (y.to == n) {
            y.to = into;
            y.T_from_to = y.T_from_to * T_n_into;
        }
        if (y.from != y.to) moved.push_back(y);
    }
    std::set<std::pair<std::uint64_t, std::uint64_t>> relayed;
    for (const auto& [a, b] : relayed_) {
        if (a != n && b != n) relayed.insert({a, b});
    }
    for (const map::PoseGraphEdge& y : moved) {
        int same = 0;
        for (const map::PoseGraphEdge& z : updated.edges()) {
            same += z.kind == y.kind && (y.kind == map::EdgeKind::kOdometry || z.active) &&
                    ((z.from == y.from && z.to == y.to) || (z.from == y.to && z.to == y.from));
        }
        const int limit = y.kind == map::EdgeKind::kOdometry ? 1
                          : max_loops_per_anchor_pair > 0    ? max_loops_per_anchor_pair
                                                             : std::numeric_limits<int>::max();
        if (same >= limit) continue;
        if (updated.add_edge(y) && y.kind == map::EdgeKind::kOdometry)
            relayed.insert({y.from, y.to});
    }
    relayed_ = std::move(relayed);
    return updated;
}

std::size_t LongTermFolding::memory_bytes() const {
    std::size_t n = 0;
    for (const auto& [session, folded] : folded_)
        n += folded.size() * (sizeof(Folded) + 48);  // map node overhead
    return n;
}

std::vector<std::pair<std::uint32_t, std::uint64_t>> LongTermFolding::retarget(
    std::uint64_t n, std::uint64_t into, const Eigen::Isometry3d& T_into_n) {
    std::vector<std::pair<std::uint32_t, std::uint64_t>> moved;
    for (auto& [session, maps] : folded_) {
        for (auto& [local_map_id, f] : maps) {
            if (f.node != n) continue;
            f.node = into;
            f.T_node_anchor = T_into_n * f.T_node_anchor;
            moved.emplace_back(session, local_map_id);
        }
    }
    return moved;
}

}  // namespace ltm::mapping
