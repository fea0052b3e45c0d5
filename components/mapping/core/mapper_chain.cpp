// The Mapper's odometry chains (see mapper.hpp): each session's local maps in id order as graph
// nodes, the odometry edge between neighbours (the weak edge across a segment break), the odometry
// path to each node, and where a new node is predicted. Split from mapper.cpp: one concept a file.
#include "mapping/core/mapper.hpp"

namespace ltm::mapping {

Eigen::Isometry3d Mapper::predicted_world(std::uint32_t session, std::uint64_t local_map_id,
                                          const Eigen::Isometry3d& T_odom_anchor) const {
    const auto chain = chains_.find(session);
    if (chain == chains_.end() || chain->second.empty()) return T_odom_anchor;
    // The nearest map of the chain, preferably an earlier one: its correction carries over.
    auto it = chain->second.lower_bound(local_map_id);
    if (it != chain->second.begin()) --it;
    const ChainAnchor a = chain_anchor(session, it->first, it->second);
    return a.T_world_anchor * a.T_odom_anchor.inverse() * T_odom_anchor;
}

std::uint64_t Mapper::ensure_node(std::uint32_t session, std::uint64_t local_map_id,
                                  const Eigen::Isometry3d& T_odom_anchor,
                                  std::optional<std::uint32_t> segment) {
    if (const std::optional<std::uint64_t> existing = node_of(local_map_id, session)) {
        if (segment && !folding_.find(session, local_map_id))
            set_segment(session, local_map_id, *segment);
        return *existing;
    }
    map::PoseGraphNode n;
    n.id = next_node_++;
    n.session = session;
    n.local_map_id = local_map_id;
    n.T_odom_anchor = T_odom_anchor;
    // Across a break too: the odometry restarted at its best estimate, in the same odometry frame.
    n.T_world_anchor = predicted_world(session, local_map_id, T_odom_anchor);
    // The optimisation holds the first node of each connected part: the first node of the map's
    // first session goes first, so that robots joined to it move, not it (and its frame).
    if (!chains_.count(session) && session == reference_session() && !graph_.nodes().empty()) {
        PoseGraph reordered(graph_.config());
        reordered.add_node(n);
        for (const map::PoseGraphNode& other : graph_.nodes()) reordered.add_node(other);
        for (const map::PoseGraphEdge& e : graph_.edges()) reordered.add_edge(e);
        graph_ = std::move(reordered);
    } else {
        graph_.add_node(n);
    }
    std::map<std::uint64_t, std::uint64_t>& chain = chains_[session];
    const auto it = chain.emplace(local_map_id, n.id).first;
    if (segment) {
        segments_.set(n.id, *segment, true);
    } else {
        // Until its local map says: the segment of the map before it (the odometry hands a
        // keyframe over before the first snapshot of its local map).
        const auto prev = it == chain.begin() ? std::next(it) : std::prev(it);
        const std::uint32_t s = prev == chain.end() ? 0 : segment_of(prev->second);
        segments_.set(n.id, s, false);
    }
    link_odometry(session, local_map_id);
    set_path(session, local_map_id);
    return n.id;
}

void Mapper::set_path(std::uint32_t session, std::uint64_t local_map_id) {
    const std::map<std::uint64_t, std::uint64_t>& chain = chains_[session];
    const auto it = chain.find(local_map_id);
    const map::PoseGraphNode* node = graph_.find(it->second);
    double path = 0.0;
    if (it != chain.begin()) {
        const ChainAnchor prev = chain_anchor(session, std::prev(it)->first, std::prev(it)->second);
        path = prev.path +
               (prev.T_odom_anchor.translation() - node->T_odom_anchor.translation()).norm();
    }
    path_at_[node->id] = path;
}

void Mapper::link_odometry(std::uint32_t session, std::uint64_t local_map_id) {
    const std::map<std::uint64_t, std::uint64_t>& chain = chains_[session];
    const auto it = chain.find(local_map_id);
    const ChainAnchor node = chain_anchor(session, it->first, it->second);
    std::optional<ChainAnchor> prev, next;
    if (it != chain.begin())
        prev = chain_anchor(session, std::prev(it)->first, std::prev(it)->second);
    if (std::next(it) != chain.end())
        next = chain_anchor(session, std::next(it)->first, std::next(it)->second);
    // Not between maps folded into earlier ones: that edge is an earlier lap's or session's.
    if (prev && next && !prev->folded && !next->folded)
        graph_.remove_edges(prev->node, next->node, map::EdgeKind::kOdometry);
    auto link = [&](const ChainAnchor& a, const ChainAnchor& b) {
        if (a.node == b.node) return;
        // Between two places already joined by an odometry edge (maps folded into earlier ones):
        // the place pair is measured; the graph does not grow with the laps.
        if ((a.folded || b.folded) && has_odometry_edge(a.node, b.node)) return;
        map::PoseGraphEdge e;
        e.from = a.node;
        e.to = b.node;
        e.kind = map::EdgeKind::kOdometry;
        e.T_from_to = a.T_node_anchor * a.T_odom_anchor.inverse() * b.T_odom_anchor *
                      b.T_node_anchor.inverse();
        // Into the first map of a new segment: the odometry's best estimate, not a measurement.
        e.information =
            a.segment == b.segment
                ? odometry_information(config_.odometry_edge, e.T_from_to.translation().norm())
                : segment_break_information();
        if (graph_.add_edge(e) && (a.folded || b.folded)) folding_.relay(e.from, e.to);
    };
    if (prev) link(*prev, node);
    if (next) link(node, *next);
}

void Mapper::unlink_odometry(std::uint32_t session, std::uint64_t local_map_id) {
    const std::map<std::uint64_t, std::uint64_t>& chain = chains_[session];
    const auto it = chain.find(local_map_id);
    if (folding_.find(session, local_map_id)) return;
    if (it != chain.begin())
        graph_.remove_edges(std::prev(it)->second, it->second, map::EdgeKind::kOdometry);
    if (std::next(it) != chain.end())
        graph_.remove_edges(it->second, std::next(it)->second, map::EdgeKind::kOdometry);
}

}  // namespace ltm::mapping
