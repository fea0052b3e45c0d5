#include "mapping/core/odometry_chains.hpp"

#include <iterator>

namespace ltm::mapping {
namespace {

bool has_odometry_edge(const PoseGraph& graph, std::uint64_t a, std::uint64_t b) {
    for (const map::PoseGraphEdge& e : graph.edges()) {
        if (e.kind == map::EdgeKind::kOdometry &&
            ((e.from == a && e.to == b) || (e.from == b && e.to == a)))
            return true;
    }
    return false;
}

}  // namespace

const OdometryChains::Chain* OdometryChains::chain(std::uint32_t session) const {
    const auto it = chains_.find(session);
    return it == chains_.end() ? nullptr : &it->second;
}

std::optional<std::uint64_t> OdometryChains::node_of(std::uint32_t session,
                                                     std::uint64_t local_map_id) const {
    const Chain* c = chain(session);
    if (!c) return std::nullopt;
    const auto it = c->find(local_map_id);
    if (it == c->end()) return std::nullopt;
    return it->second;
}

void OdometryChains::set(std::uint32_t session, std::uint64_t local_map_id, std::uint64_t node) {
    chains_[session][local_map_id] = node;
}

OdometryChains::Chain::const_iterator OdometryChains::insert(std::uint32_t session,
                                                             std::uint64_t local_map_id,
                                                             std::uint64_t node) {
    return chains_[session].emplace(local_map_id, node).first;
}

double OdometryChains::path(std::uint64_t node) const {
    const auto p = path_at_.find(node);
    return p == path_at_.end() ? 0.0 : p->second;
}

OdometryChains::Anchor OdometryChains::anchor(const View& view, std::uint32_t session,
                                              std::uint64_t local_map_id,
                                              std::uint64_t node) const {
    Anchor a;
    a.node = node;
    const map::PoseGraphNode* n = view.graph.find(node);
    if (const LongTermFolding::Folded* f = view.folding.find(session, local_map_id)) {
        a.folded = true;
        a.T_node_anchor = f->T_node_anchor;
        a.T_odom_anchor = f->T_odom_anchor;
        a.T_world_anchor = n->T_world_anchor * f->T_node_anchor;
        a.segment = f->segment;
        a.path = f->path;
        return a;
    }
    a.T_odom_anchor = n->T_odom_anchor;
    a.T_world_anchor = n->T_world_anchor;
    a.segment = view.segments.of(node);
    a.path = path(node);
    return a;
}

Eigen::Isometry3d OdometryChains::predicted_world(const View& view, std::uint32_t session,
                                                  std::uint64_t local_map_id,
                                                  const Eigen::Isometry3d& T_odom_anchor) const {
    const Chain* c = chain(session);
    if (!c || c->empty()) return T_odom_anchor;
    auto it = c->lower_bound(local_map_id);
    if (it != c->begin()) --it;
    const Anchor a = anchor(view, session, it->first, it->second);
    return a.T_world_anchor * a.T_odom_anchor.inverse() * T_odom_anchor;
}

void OdometryChains::set_path(const View& view, std::uint32_t session, std::uint64_t local_map_id) {
    const Chain& c = chains_[session];
    const auto it = c.find(local_map_id);
    const map::PoseGraphNode* node = view.graph.find(it->second);
    double p = 0.0;
    if (it != c.begin()) {
        const Anchor prev = anchor(view, session, std::prev(it)->first, std::prev(it)->second);
        p = prev.path +
            (prev.T_odom_anchor.translation() - node->T_odom_anchor.translation()).norm();
    }
    path_at_[node->id] = p;
}

void OdometryChains::link(PoseGraph* graph, const Segments& segments, LongTermFolding* folding,
                          const OdometryEdgeConfig& config, std::uint32_t session,
                          std::uint64_t local_map_id) {
    const View view{*graph, segments, *folding};
    const Chain& c = chains_[session];
    const auto it = c.find(local_map_id);
    const Anchor node = anchor(view, session, it->first, it->second);
    std::optional<Anchor> prev, next;
    if (it != c.begin()) prev = anchor(view, session, std::prev(it)->first, std::prev(it)->second);
    if (std::next(it) != c.end())
        next = anchor(view, session, std::next(it)->first, std::next(it)->second);
    // Not between maps folded into earlier ones: that edge is an earlier lap's or session's.
    if (prev && next && !prev->folded && !next->folded)
        graph->remove_edges(prev->node, next->node, map::EdgeKind::kOdometry);
    auto join = [&](const Anchor& a, const Anchor& b) {
        if (a.node == b.node) return;
        // Between two places already joined by an odometry edge (maps folded into earlier ones):
        // the place pair is measured; the graph does not grow with the laps.
        if ((a.folded || b.folded) && has_odometry_edge(*graph, a.node, b.node)) return;
        map::PoseGraphEdge e;
        e.from = a.node;
        e.to = b.node;
        e.kind = map::EdgeKind::kOdometry;
        e.T_from_to = a.T_node_anchor * a.T_odom_anchor.inverse() * b.T_odom_anchor *
                      b.T_node_anchor.inverse();
        // Into the first map of a new segment: the odometry's best estimate, not a measurement.
        e.information = a.segment == b.segment
                            ? odometry_information(config, e.T_from_to.translation().norm())
                            : segment_break_information();
        if (graph->add_edge(e) && (a.folded || b.folded)) folding->relay(e.from, e.to);
    };
    if (prev) join(*prev, node);
    if (next) join(node, *next);
}

void OdometryChains::unlink(PoseGraph* graph, const LongTermFolding& folding, std::uint32_t session,
                            std::uint64_t local_map_id) const {
    const Chain& c = chains_.at(session);
    const auto it = c.find(local_map_id);
    if (folding.find(session, local_map_id)) return;
    if (it != c.begin())
        graph->remove_edges(std::prev(it)->second, it->second, map::EdgeKind::kOdometry);
    if (std::next(it) != c.end())
        graph->remove_edges(it->second, std::next(it)->second, map::EdgeKind::kOdometry);
}

std::size_t OdometryChains::memory_bytes() const {
    std::size_t n = 0;
    for (const auto& [session, c] : chains_) n += c.size() * 48;  // map node overhead
    return n;
}

}  // namespace ltm::mapping
