#include "mapping/core/session_joins.hpp"

#include <cmath>
#include <set>

namespace ltm::mapping {

bool SessionJoins::confirm(const SegmentKey& match_root, const SegmentKey& query_root,
                           const map::PoseGraphEdge& edge, const LoopClosure& loop,
                           const PoseGraph& graph, const Segments& segments,
                           std::vector<Join>* agreed) {
    const SessionJoinConfig& sj = config_;
    if (sj.loops <= 1) return true;
    // Where the `to` side's part lies in the `from` side's, by a loop: the correction of the
    // `to` part, C = T_from * Z * T_to^-1 (world poses as of now); between the same two parts
    // either way round.
    auto correction = [&graph](const map::PoseGraphEdge& x) {
        return graph.find(x.from)->T_world_anchor * x.T_from_to *
               graph.find(x.to)->T_world_anchor.inverse();
    };
    std::vector<std::size_t> agreeing;
    for (std::size_t i = 0; i < held_.size(); ++i) {
        const Held& h = held_[i];
        const map::PoseGraphEdge& held_edge = h.join.edge;
        if (!graph.find(held_edge.from) || !graph.find(held_edge.to)) continue;  // folded since
        if (!segments.known(held_edge.from) || !segments.known(held_edge.to)) continue;
        const bool same_way = h.match_root == match_root && h.query_root == query_root;
        const bool other_way = h.match_root == query_root && h.query_root == match_root;
        if (!same_way && !other_way) continue;
        // The held loop's correction, for this loop's `to` part; what it predicts for this edge.
        const Eigen::Isometry3d C =
            same_way ? correction(held_edge) : Eigen::Isometry3d(correction(held_edge).inverse());
        const Eigen::Isometry3d predicted = graph.find(edge.from)->T_world_anchor.inverse() * C *
                                            graph.find(edge.to)->T_world_anchor;
        const Eigen::Isometry3d D = predicted.inverse() * edge.T_from_to;
        if (D.translation().norm() <= sj.agree_translation &&
            Eigen::AngleAxisd(D.linear()).angle() * 180.0 / M_PI <= sj.agree_rotation)
            agreeing.push_back(i);
    }
    // ... from at least two keyframes (the candidates of one keyframe share its odometry, right
    // or wrong), and only where both nodes' segments are known: the odometry hands a new local
    // map's first keyframes over before the map that says it starts a new segment (a robot
    // lifted and set down, say), and until then the node belongs to the segment before it.
    std::set<std::pair<std::uint32_t, std::uint32_t>> keyframes = {
        {loop.query_session, loop.query_keyframe}};
    for (const std::size_t i : agreeing)
        keyframes.insert({held_[i].join.loop.query_session, held_[i].join.loop.query_keyframe});
    if (agreeing.size() + 1 < std::size_t(sj.loops) || keyframes.size() < 2 ||
        !segments.known(edge.from) || !segments.known(edge.to)) {
        held_.push_back(Held{match_root, query_root, Join{edge, loop}});
        constexpr std::size_t kMaxHeld = 256;
        if (held_.size() > kMaxHeld) held_.erase(held_.begin());
        return false;
    }
    for (const std::size_t i : agreeing) agreed->push_back(held_[i].join);
    // Those two parts are joined now: what else was held between them is dropped.
    std::vector<Held> kept;
    for (Held& h : held_) {
        const bool pair = (h.match_root == match_root && h.query_root == query_root) ||
                          (h.match_root == query_root && h.query_root == match_root);
        if (!pair) kept.push_back(std::move(h));
    }
    held_ = std::move(kept);
    return true;
}

}  // namespace ltm::mapping
