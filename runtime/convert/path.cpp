#include "runtime/convert/path.hpp"

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {
namespace {

void fill(const common::StampedPose& in, const std::string& frame_id, msg::PoseStamped& out) {
    out.header.stamp = to_time(in.stamp);
    set_string(out.header.frame_id, frame_id);
    out.pose = to_pose(in.pose);
}

}  // namespace

Owned<msg::PoseStamped> to_msg(const common::StampedPose& pose, const std::string& frame_id) {
    Owned<msg::PoseStamped> m;
    fill(pose, frame_id, *m);
    return m;
}

common::StampedPose from_msg(const msg::PoseStamped& m) {
    common::StampedPose p;
    p.stamp = to_seconds(m.header.stamp);
    p.pose = to_isometry(m.pose);
    return p;
}

Owned<msg::Path> to_msg(const common::Trajectory& poses, const std::string& frame_id,
                        double stamp) {
    Owned<msg::Path> m;
    m->header.stamp = to_time(stamp);
    set_string(m->header.frame_id, frame_id);
    msg::PoseStamped* out = alloc_sequence(m->poses, poses.size());
    for (std::size_t i = 0; i < poses.size(); ++i) fill(poses[i], frame_id, out[i]);
    return m;
}

common::Trajectory from_msg(const msg::Path& m) {
    common::Trajectory t;
    t.reserve(m.poses._length);
    for (const msg::PoseStamped& p : view(m.poses)) t.push_back(from_msg(p));
    return t;
}

}  // namespace ltm::convert
