// The Mapper's odometry segments and sessions on the map (see mapper.hpp; the segments and their
// placement are Segments'): a segment told late relinks the chain after it, a segment not yet
// joined by a loop is placed at the odometry's estimate across its break, and the status of every
// segment and session.
#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "mapping/core/mapper.hpp"

namespace ltm::mapping {

std::uint32_t Mapper::segment_of(std::uint64_t node) const { return segments_.of(node); }

void Mapper::set_segment(std::uint32_t session, std::uint64_t local_map_id, std::uint32_t segment) {
    const OdometryChains::Chain& chain = *chains_.chain(session);
    auto it = chain.find(local_map_id);
    if (!segments_.tell(it->second, segment)) return;
    // The maps after it that only took their segment from it take the new one too.
    std::vector<std::uint64_t> relink = {local_map_id};
    for (auto next = std::next(it); next != chain.end(); ++next) {
        if (folding_.find(session, next->first)) break;  // finished, so told
        if (!segments_.follow(next->second, segment)) break;
        relink.push_back(next->first);
    }
    for (const std::uint64_t id : relink) {
        chains_.unlink(&graph_, folding_, session, id);
        chains_.link(&graph_, segments_, &folding_, config_.odometry_edge, session, id);
    }
}

void Mapper::place_unjoined_segments() {
    for (const auto& [session, chain] : chains_.all()) {
        std::optional<ChainAnchor> prev;
        for (const auto& [local_map_id, id] : chain) {
            const ChainAnchor node = chains_.anchor(view(), session, local_map_id, id);
            const SegmentKey key = segments_.key(graph_, id);
            // A folded map was tied by a loop: it starts no unjoined part.
            const bool starts_part = prev && !node.folded && prev->segment != node.segment &&
                                     segments_.root(key) == key &&
                                     segments_.root(graph_, prev->node) != key;
            if (starts_part) {
                // The first map of a segment that no loop joins to anything before it: its part
                // is placed by the edge across the break alone, at the odometry's best estimate
                // relative to the map before it. That is the optimum, which the solver approaches
                // only slowly (the edge weighs next to nothing): set it here exactly.
                const Eigen::Isometry3d C = prev->T_world_anchor * prev->T_odom_anchor.inverse() *
                                            node.T_odom_anchor * node.T_world_anchor.inverse();
                std::vector<std::uint64_t> part;
                bool fixed = false;
                for (const map::PoseGraphNode& n : graph_.nodes()) {
                    if (segments_.root(graph_, n.id) != key) continue;
                    part.push_back(n.id);
                    fixed = fixed || n.fixed;
                }
                if (!fixed) {
                    for (const std::uint64_t p : part)
                        graph_.set_pose(p, C * graph_.find(p)->T_world_anchor);
                }
            }
            prev = chains_.anchor(view(), session, local_map_id, id);
        }
    }
}

std::vector<SegmentStatus> Mapper::segments() const { return segments(session_); }

std::vector<SegmentStatus> Mapper::segments(std::uint32_t session) const {
    std::vector<SegmentStatus> out;
    const OdometryChains::Chain* chain = chains_.chain(session);
    if (!chain || !is_open(session)) return out;
    // What counts as the map: this session's segment 0 and whatever it is joined to, and every
    // earlier session.
    const SegmentKey first = segments_.root(SegmentKey(session, 0));
    auto on_map = [&](const SegmentKey& k) {
        const SegmentKey r = segments_.root(k);
        return r.first < session || r == first;
    };
    for (const auto& [local_map_id, node] : *chain) {
        const Folded* f = folding_.find(session, local_map_id);
        const std::uint32_t s = f ? f->segment : segment_of(node);
        if (!out.empty() && out.back().segment == s) continue;
        SegmentStatus st;
        st.segment = s;
        st.first_local_map = local_map_id;
        st.joined = s == 0 || on_map(SegmentKey(session, s));
        std::ostringstream m;
        if (s == 0) {
            m << "segment 0: the session's first";
        } else if (st.joined) {
            // The earliest active loop between this segment and another one.
            bool found = false;
            for (const map::PoseGraphEdge& e : graph_.edges()) {
                if (e.kind != map::EdgeKind::kLoop || !e.active) continue;
                const SegmentKey a = segments_.key(graph_, e.from), b = segments_.key(graph_, e.to);
                if (a == b || (a != SegmentKey(session, s) && b != SegmentKey(session, s)))
                    continue;
                const std::uint32_t k = std::uint32_t(e.query_keyframe);
                if (!found || k < st.joined_at_keyframe) st.joined_at_keyframe = k;
                found = true;
            }
            m << "segment " << s << " joined to the map by a loop at keyframe "
              << st.joined_at_keyframe;
        } else {
            m << "segment " << s << " (from local map " << local_map_id
              << ") not joined to the map yet: its poses, corrected_odometry and map_to_odom are "
                 "the odometry's best estimate across the break";
        }
        st.message = m.str();
        out.push_back(st);
    }
    return out;
}

std::size_t Mapper::placed_parts() const { return segments_.placed_parts(graph_); }

std::uint32_t Mapper::reference_session() const {
    return chains_.all().empty() ? session_ : std::min(chains_.all().begin()->first, session_);
}

SessionStatus Mapper::session_status(std::uint32_t session) const {
    SessionStatus st;
    st.session = session;
    st.robot = robot(session);
    std::ostringstream name;
    name << "session " << session;
    if (!st.robot.empty()) name << " (" << st.robot << ")";
    if (!is_open(session)) {
        st.message = name.str() + " is not open";
        return st;
    }
    const std::uint32_t reference = reference_session();
    const SegmentKey own = segments_.root(SegmentKey(session, 0));
    std::ostringstream m;
    if (session == reference) {
        st.joined = true;
        m << name.str() << ": the map's first";
    } else if (own == segments_.root(SegmentKey(reference, 0))) {
        st.joined = true;
        // The earliest active loop between this session and another one.
        bool found = false;
        for (const map::PoseGraphEdge& e : graph_.edges()) {
            if (e.kind != map::EdgeKind::kLoop || !e.active) continue;
            const std::uint32_t a = segments_.key(graph_, e.from).first,
                                b = segments_.key(graph_, e.to).first;
            if (a == b || (a != session && b != session)) continue;
            const std::uint32_t k = std::uint32_t(e.query_keyframe);
            if (!found || k < st.joined_at_keyframe) st.joined_at_keyframe = k;
            found = true;
        }
        m << name.str() << " joined to the map by a loop at keyframe " << st.joined_at_keyframe;
    } else if (!chains_.has(session)) {
        m << name.str() << " has no local map yet";
    } else {
        m << name.str()
          << " not joined to the map yet: its poses, corrected_odometry and map_to_odom are its "
             "own odometry's, from where it started";
    }
    st.message = m.str();
    return st;
}

}  // namespace ltm::mapping
