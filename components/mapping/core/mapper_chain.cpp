// A local map's graph node (mapper.hpp): a new one placed where its odometry chain predicts it,
// in the chain (OdometryChains) and its segment (Segments), linked to its neighbours by odometry.
#include "mapping/core/mapper.hpp"

namespace ltm::mapping {

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
    n.T_world_anchor = chains_.predicted_world(view(), session, local_map_id, T_odom_anchor);
    // The optimisation holds the first node of each connected part: the first node of the map's
    // first session goes first, so that robots joined to it move, not it (and its frame).
    if (!chains_.has(session) && session == reference_session() && !graph_.nodes().empty()) {
        PoseGraph reordered(graph_.config());
        reordered.add_node(n);
        for (const map::PoseGraphNode& other : graph_.nodes()) reordered.add_node(other);
        for (const map::PoseGraphEdge& e : graph_.edges()) reordered.add_edge(e);
        graph_ = std::move(reordered);
    } else {
        graph_.add_node(n);
    }
    const auto it = chains_.insert(session, local_map_id, n.id);
    const OdometryChains::Chain& chain = *chains_.chain(session);
    if (segment) {
        segments_.set(n.id, *segment, true);
    } else {
        // Until its local map says: the segment of the map before it (the odometry hands a
        // keyframe over before the first snapshot of its local map).
        const auto prev = it == chain.begin() ? std::next(it) : std::prev(it);
        const std::uint32_t s = prev == chain.end() ? 0 : segment_of(prev->second);
        segments_.set(n.id, s, false);
    }
    chains_.link(&graph_, segments_, &folding_, config_.odometry_edge, session, local_map_id);
    chains_.set_path(view(), session, local_map_id);
    return n.id;
}

}  // namespace ltm::mapping
