#include "runtime/convert/transform.hpp"

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {

msg::Transform to_transform(const Eigen::Isometry3d& T) {
    const msg::Pose p = to_pose(T);
    return {{p.position.x, p.position.y, p.position.z}, p.orientation};
}

Eigen::Isometry3d to_isometry(const msg::Transform& t) {
    msg::Pose p;
    p.position = {t.translation.x, t.translation.y, t.translation.z};
    p.orientation = t.rotation;
    return to_isometry(p);
}

Owned<msg::TransformStamped> to_msg(const TransformData& t) {
    Owned<msg::TransformStamped> m;
    m->header.stamp = t.stamp;
    set_string(m->header.frame_id, t.parent_frame_id);
    set_string(m->child_frame_id, t.child_frame_id);
    m->transform = to_transform(t.T_parent_child);
    return m;
}

TransformData from_msg(const msg::TransformStamped& m) {
    TransformData t;
    t.stamp = m.header.stamp;
    t.parent_frame_id = to_string(m.header.frame_id);
    t.child_frame_id = to_string(m.child_frame_id);
    t.T_parent_child = to_isometry(m.transform);
    return t;
}

}  // namespace ltm::convert
