#include "mapping/component/mapper_messages.hpp"

#include <map>

namespace ltm::mapping {

convert::PoseGraphData graph_data(const Mapper& mapper, const std::string& frame_id) {
    const PoseGraph& g = mapper.graph();
    convert::PoseGraphData out;
    out.frame_id = frame_id;
    out.revision = static_cast<std::uint32_t>(mapper.revision());
    std::map<std::uint64_t, std::uint64_t> map_of;  // node id -> local map id
    for (const auto& n : g.nodes()) {
        out.anchors.push_back({n.local_map_id, n.T_world_anchor});
        map_of[n.id] = n.local_map_id;
    }
    for (const auto& e : g.edges()) {
        if (!e.active) continue;
        const auto kind = e.kind == map::EdgeKind::kOdometry ? convert::GraphEdgeKind::kOdometry
                                                             : convert::GraphEdgeKind::kLoop;
        out.edges.push_back({map_of[e.from], map_of[e.to], kind, e.T_from_to, e.information});
    }
    return out;
}

convert::LoopClosureData loop_data(const Mapper& mapper, const LoopClosure& loop,
                                   const msg::Time& stamp, const std::string& frame_id) {
    convert::LoopClosureData out;
    out.stamp = stamp;
    out.frame_id = frame_id;
    for (const auto& n : mapper.graph().nodes()) {
        if (n.id == loop.from_node) out.from_map_id = n.local_map_id;
        if (n.id == loop.to_node) out.to_map_id = n.local_map_id;
    }
    out.from_keyframe_id = loop.match_keyframe;
    out.to_keyframe_id = loop.query_keyframe;
    out.T_from_to = loop.T_from_to;
    out.information = loop_information(mapper.config().loop_edge);
    out.score = static_cast<float>(loop.descriptor_distance);
    out.fitness = static_cast<float>(loop.inlier_fraction);
    out.residual = static_cast<float>(loop.inlier_rms);
    out.accepted = true;
    return out;
}

common::Trajectory session_path(const Mapper& mapper) {
    return session_path(mapper, mapper.session());
}

common::Trajectory session_path(const Mapper& mapper, std::uint32_t session) {
    const auto& keyframes = mapper.keyframes();
    common::Trajectory poses;
    poses.reserve(keyframes.size());
    for (std::uint32_t i = 0; i < keyframes.size(); ++i) {
        if (keyframes[i]->session != session) continue;  // a loaded map's, another robot's
        poses.push_back({keyframes[i]->data.stamp, mapper.keyframe_pose(i)});
    }
    return poses;
}

}  // namespace ltm::mapping
