#include "runtime/convert/pose_graph.hpp"

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {

Owned<msg::PoseGraph> to_msg(const PoseGraphData& g) {
    Owned<msg::PoseGraph> m;
    m->header.stamp = g.stamp;
    set_string(m->header.frame_id, g.frame_id);
    m->revision = g.revision;
    msg::AnchorPose* anchors = alloc_sequence(m->anchors, g.anchors.size());
    for (std::size_t i = 0; i < g.anchors.size(); ++i)
        anchors[i] = {g.anchors[i].local_map_id, to_pose(g.anchors[i].T_map_anchor)};
    msg::PoseGraphEdge* edges = alloc_sequence(m->edges, g.edges.size());
    for (std::size_t i = 0; i < g.edges.size(); ++i) {
        const GraphEdge& e = g.edges[i];
        edges[i].from_id = e.from_map_id;
        edges[i].to_id = e.to_map_id;
        edges[i].kind = static_cast<std::uint8_t>(e.kind);
        edges[i].relative_pose = to_pose(e.T_from_to);
        to_array36(e.information, edges[i].information);
    }
    return m;
}

PoseGraphData from_msg(const msg::PoseGraph& m) {
    PoseGraphData g;
    g.stamp = m.header.stamp;
    g.frame_id = to_string(m.header.frame_id);
    g.revision = m.revision;
    for (const msg::AnchorPose& a : view(m.anchors))
        g.anchors.push_back({a.id, to_isometry(a.pose)});
    for (const msg::PoseGraphEdge& e : view(m.edges))
        g.edges.push_back({e.from_id, e.to_id, static_cast<GraphEdgeKind>(e.kind),
                           to_isometry(e.relative_pose), from_array36(e.information)});
    return g;
}

}  // namespace ltm::convert
