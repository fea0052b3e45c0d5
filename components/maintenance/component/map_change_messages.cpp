#include "maintenance/component/map_change_messages.hpp"

#include <cstring>
#include <stdexcept>

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::maintenance {
namespace {

msg::Point to_point(const Eigen::Vector3f& p) {
    return {double(p.x()), double(p.y()), double(p.z())};
}

Eigen::Vector3f from_point(const msg::Point& p) {
    return {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
}

}  // namespace

std::uint8_t to_msg_reason(ChangeReason reason) {
    switch (reason) {
        case ChangeReason::kMoving:
            return ltm_msgs_msg_SegmentChange_Constants_MOVING;
        case ChangeReason::kVanished:
            return ltm_msgs_msg_SegmentChange_Constants_VANISHED;
        case ChangeReason::kNew:
            return ltm_msgs_msg_SegmentChange_Constants_NEW;
    }
    return ltm_msgs_msg_SegmentChange_Constants_MOVING;
}

convert::Owned<msg::MapChangeSet> to_msg(const ChangeSet& c, std::uint32_t pass, double stamp,
                                         const std::string& frame_id) {
    convert::Owned<msg::MapChangeSet> m;
    m->header.stamp = convert::to_time(stamp);
    convert::set_string(m->header.frame_id, frame_id);
    m->pass = pass;
    m->session = c.session;
    m->map_time = c.map_time;
    m->voxel_size = c.voxel_size;
    m->voxels_before = c.voxels_before;
    m->voxels_removed = c.voxels_removed;
    m->voxels_judged = c.voxels_judged;
    m->segments = c.segments;
    m->ground_voxels = c.ground_voxels;
    m->time_ms = c.time_ms;
    msg::SegmentChange* out = convert::alloc_sequence(m->changes, c.changes.size());
    for (const SegmentChange& s : c.changes) {
        msg::SegmentChange& o = *out++;
        o.id = s.id;
        o.reason = to_msg_reason(s.reason);
        o.region[0] = s.region.x();
        o.region[1] = s.region.y();
        o.centroid = to_point(s.centroid);
        o.bbox_min = to_point(s.bbox_min);
        o.bbox_max = to_point(s.bbox_max);
        o.first_seen = s.first_seen;
        o.last_seen = s.last_seen;
        o.score = s.score;
        o.judged = s.judged;
        float* v = convert::alloc_sequence(o.voxels, 3 * s.voxels.size());
        for (const Eigen::Vector3f& p : s.voxels) {
            std::memcpy(v, p.data(), 3 * sizeof(float));
            v += 3;
        }
    }
    return m;
}

ChangeSet from_msg(const msg::MapChangeSet& m) {
    ChangeSet c;
    c.session = m.session;
    c.map_time = m.map_time;
    c.voxel_size = m.voxel_size;
    c.voxels_before = m.voxels_before;
    c.voxels_removed = m.voxels_removed;
    c.voxels_judged = m.voxels_judged;
    c.segments = m.segments;
    c.ground_voxels = m.ground_voxels;
    c.time_ms = m.time_ms;
    const auto changes = convert::view(m.changes);
    c.changes.resize(changes.size());
    for (std::uint32_t i = 0; i < changes.size(); ++i) {
        const msg::SegmentChange& o = changes[i];
        SegmentChange& s = c.changes[i];
        const std::string which = "map change set: changes[" + std::to_string(i) + "]";
        if (o.reason > ltm_msgs_msg_SegmentChange_Constants_NEW)
            throw std::invalid_argument(which + ": unknown reason " + std::to_string(o.reason));
        s.id = o.id;
        s.reason = static_cast<ChangeReason>(o.reason);
        s.region = {o.region[0], o.region[1]};
        s.centroid = from_point(o.centroid);
        s.bbox_min = from_point(o.bbox_min);
        s.bbox_max = from_point(o.bbox_max);
        s.first_seen = o.first_seen;
        s.last_seen = o.last_seen;
        s.score = o.score;
        s.judged = o.judged;
        const auto v = convert::view(o.voxels);
        if (v.size() % 3 != 0)
            throw std::invalid_argument(which + ": " + std::to_string(v.size()) +
                                        " voxel coordinates, not x y z triples");
        s.voxels.resize(v.size() / 3);
        for (std::uint32_t k = 0; k < s.voxels.size(); ++k)
            s.voxels[k] = {v[3 * k], v[3 * k + 1], v[3 * k + 2]};
    }
    return c;
}

}  // namespace ltm::maintenance
