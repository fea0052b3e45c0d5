#include "runtime/convert/loop_closure.hpp"

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {

Owned<msg::LoopClosure> to_msg(const LoopClosureData& l) {
    Owned<msg::LoopClosure> m;
    m->header.stamp = l.stamp;
    set_string(m->header.frame_id, l.frame_id);
    m->from_map_id = l.from_map_id;
    m->to_map_id = l.to_map_id;
    m->from_keyframe_id = l.from_keyframe_id;
    m->to_keyframe_id = l.to_keyframe_id;
    m->relative_pose = to_pose(l.T_from_to);
    to_array36(l.information, m->information);
    m->score = l.score;
    m->fitness = l.fitness;
    m->residual = l.residual;
    m->accepted = l.accepted;
    return m;
}

LoopClosureData from_msg(const msg::LoopClosure& m) {
    LoopClosureData l;
    l.stamp = m.header.stamp;
    l.frame_id = to_string(m.header.frame_id);
    l.from_map_id = m.from_map_id;
    l.to_map_id = m.to_map_id;
    l.from_keyframe_id = m.from_keyframe_id;
    l.to_keyframe_id = m.to_keyframe_id;
    l.T_from_to = to_isometry(m.relative_pose);
    l.information = from_array36(m.information);
    l.score = m.score;
    l.fitness = m.fitness;
    l.residual = m.residual;
    l.accepted = m.accepted;
    return l;
}

}  // namespace ltm::convert
