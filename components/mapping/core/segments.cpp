#include "mapping/core/segments.hpp"

#include <algorithm>
#include <set>

#include "mapping/core/mapper_config.hpp"

namespace ltm::mapping {

std::uint32_t Segments::of(std::uint64_t node) const {
    const auto it = of_.find(node);
    return it == of_.end() ? 0 : it->second.segment;
}

bool Segments::known(std::uint64_t node) const {
    const auto it = of_.find(node);
    return it == of_.end() || it->second.told;
}

void Segments::set(std::uint64_t node, std::uint32_t segment, bool told) {
    of_[node] = NodeSegment{segment, told};
}

bool Segments::tell(std::uint64_t node, std::uint32_t segment) {
    NodeSegment& own = of_[node];
    const bool changed = own.segment != segment;
    own = NodeSegment{segment, true};
    return changed;
}

bool Segments::follow(std::uint64_t node, std::uint32_t segment) {
    NodeSegment& n = of_[node];
    if (n.told) return false;
    n.segment = segment;
    return true;
}

void Segments::forget(std::uint64_t node) { of_.erase(node); }

SegmentKey Segments::key(const PoseGraph& graph, std::uint64_t node) const {
    const map::PoseGraphNode* n = graph.find(node);
    return {n ? n->session : 0, of(node)};
}

SegmentKey Segments::root(const SegmentKey& key) const {
    const auto it = placed_.find(key);
    return it == placed_.end() ? key : it->second;
}

void Segments::update_placement(const PoseGraph& graph) {
    // Union-find over (session, segment) by the active loop edges: the graph's estimate of the
    // relative pose of two segments means something once an optimisation has placed them by loops.
    std::map<SegmentKey, SegmentKey> parent;
    auto root = [&](SegmentKey k) {
        for (auto it = parent.find(k); it != parent.end() && it->second != k; it = parent.find(k))
            k = it->second;
        return k;
    };
    // An odometry edge between two segments that is not a break joins them too: one made through
    // a local map folded into another session's (the chain goes on from that map), where the loop
    // that tied them has gone with the fold.
    for (const map::PoseGraphEdge& e : graph.edges()) {
        const bool joins = e.kind == map::EdgeKind::kLoop ? e.active : !is_segment_break(e);
        if (!joins) continue;
        const SegmentKey a = root(key(graph, e.from)), b = root(key(graph, e.to));
        if (a == b) continue;
        parent.emplace(a, a);
        parent.emplace(b, b);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    placed_.clear();
    for (const auto& [k, up] : parent) placed_[k] = root(k);
}

std::size_t Segments::placed_parts(const PoseGraph& graph) const {
    std::set<SegmentKey> roots;
    for (const map::PoseGraphNode& n : graph.nodes()) roots.insert(root(graph, n.id));
    return roots.size();
}

}  // namespace ltm::mapping
