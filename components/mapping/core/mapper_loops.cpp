// The Mapper's loop verification (see mapper.hpp): a keyframe's descriptor candidates checked
// against their local maps (from the graph's estimate within a joined segment, then from the
// descriptor's guess), the drift bound, and the accepted loops as graph edges. Split from
// mapper.cpp: one concept a file.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <unordered_map>

#include "mapping/core/drift_distance.hpp"
#include "mapping/core/mapper.hpp"

namespace ltm::mapping {
namespace {

// T turned by `yaw` about its own z axis (the descriptor's yaw guess).
Eigen::Isometry3d yawed(const Eigen::Isometry3d& T, double yaw) {
    Eigen::Isometry3d out = T;
    out.linear() = T.linear() * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return out;
}

}  // namespace

void Mapper::add_place_candidates(std::uint32_t session, std::uint64_t node,
                                  const Eigen::Isometry3d& T_anchor_lidar,
                                  const places::ScanContext& descriptor,
                                  std::vector<LoopCandidate>* candidates) const {
    const double radius = config_.place_candidates.radius;
    const map::PoseGraphNode* own = graph_.find(node);
    if (!config_.loop_closure || !config_.verify_from_graph || !(radius > 0.0) || !own ||
        live_.size() < 2)
        return;  // off, or no other robot's session open
    const SegmentKey root = segments_.root(graph_, node);
    const Eigen::Vector3d at = (own->T_world_anchor * T_anchor_lidar).translation();
    std::set<std::uint64_t> listed;  // the descriptor's candidates' local maps: verified anyway
    for (const LoopCandidate& c : *candidates) listed.insert(keyframes_[c.match]->node);
    // Per local map: another open session's, placed with this keyframe's part by loops (the graph
    // knows where it lies), received, and not yet joined to this one by enough loops.
    std::unordered_map<std::uint64_t, bool> eligible;
    auto usable = [&](std::uint64_t n) {
        const auto [it, fresh] = eligible.try_emplace(n, false);
        if (!fresh) return it->second;
        const SegmentKey key = segments_.key(graph_, n);
        const int pair_limit = config_.max_loops_per_anchor_pair;
        it->second = n != node && !listed.count(n) && key.first != session && is_open(key.first) &&
                     segments_.root(key) == root && maps_.count(n) > 0 &&
                     (pair_limit == 0 || loops_between(n, node) < pair_limit);
        return it->second;
    };
    double best = radius * radius;
    std::optional<std::uint32_t> nearest;
    for (std::uint32_t i = 0; i < keyframes_.size(); ++i) {
        const map::StoredKeyframe& k = *keyframes_[i];
        const map::PoseGraphNode* n = graph_.find(k.node);
        if (!n) continue;
        const double d2 =
            ((n->T_world_anchor * k.data.T_anchor_lidar).translation() - at).squaredNorm();
        if (d2 <= best && usable(k.node)) {  // only the maps within reach are judged
            best = d2;
            nearest = i;
        }
    }
    if (!nearest) return;
    const places::ScanContextMatch m =
        compare(descriptor, keyframes_[*nearest]->descriptor, config_.scan_context);
    LoopCandidate c;
    c.match = *nearest;
    c.distance = m.valid ? m.distance : std::numeric_limits<double>::quiet_NaN();
    c.yaw = m.yaw;
    c.shift = m.shift;
    c.by_place = true;
    candidates->push_back(c);
}

void Mapper::verify(std::uint32_t session, const common::KeyframeData& keyframe,
                    const std::vector<Eigen::Vector3f>& points, std::uint64_t node,
                    const std::vector<LoopCandidate>& candidates, KeyframeResult* r) {
    for (const LoopCandidate& c : candidates) {
        if (r->loops.size() >= std::size_t(config_.max_loops_per_keyframe)) break;
        const map::StoredKeyframe& match = *keyframes_[c.match];
        LoopRejection rejection{c.match, c.distance, ""};
        const auto entry = maps_.find(match.node);
        if (match.node == node) {
            rejection.reason = "candidate is in the same local map";
        } else if (entry == maps_.end()) {
            rejection.reason = "the candidate's local map was not received";
        } else if (!page_in(match.node, entry->second)) {
            rejection.reason = "the candidate's local map is unavailable (paged out, unreadable)";
        } else if (config_.max_loops_per_anchor_pair > 0 &&
                   loops_between(match.node, node) >= config_.max_loops_per_anchor_pair) {
            // Local maps are rigid: another loop between the same two anchors measures the same
            // relative pose again (and costs a verification and an edge to optimise).
            rejection.reason = "the two local maps are already joined by a loop";
        }
        if (!rejection.reason.empty()) {
            r->rejected.push_back(rejection);
            continue;
        }
        // The graph's estimate of the query anchor in the match anchor: within one session, the
        // odometry bounds its error; it is a first guess and the consistency check below. Not
        // across a segment break that no optimised loop joins yet: there it is only the
        // odometry's guess across the break (metres and tens of degrees off), so the descriptor's
        // guess is the one that counts and the verification's quality alone decides. The same
        // between two robots' sessions (open at once) that no optimised loop placed together yet.
        const Eigen::Isometry3d predicted =
            graph_.find(match.node)->T_world_anchor.inverse() * graph_.find(node)->T_world_anchor;
        const bool same_session = match.session == session;
        const SegmentKey match_key = segments_.key(graph_, match.node),
                         query_key = segments_.key(graph_, node);
        const bool together = segments_.root(match_key) == segments_.root(query_key);
        // With a localisation on the loaded map (expect_map_fixes), it places a part on that map
        // (a repetitive site can fool one loop verification from a descriptor's guess), and loops
        // to the loaded map from a part it placed are judged against the graph like any other.
        const bool loaded_match = !is_open(match.session);
        if (fixes_expected_ && loaded_match && !together) {
            rejection.reason = "held: the localisation places this part on the loaded map first";
            r->rejected.push_back(rejection);
            continue;
        }
        const bool placed = together && (same_session || is_open(match.session) || fixes_expected_);
        registration::GuessList guesses;
        const bool graph_guess = placed && config_.verify_from_graph;
        if (graph_guess) guesses.push_back(predicted * keyframe.T_anchor_lidar);
        // A candidate by place: the graph's estimate only (the descriptors did not match).
        if (!c.by_place) guesses.push_back(yawed(match.data.T_anchor_lidar, c.yaw));
        if (guesses.empty()) {
            rejection.reason = "a candidate by place whose part is not placed with this one";
            r->rejected.push_back(rejection);
            continue;
        }
        const registration::LoopVerification v =
            verifier_.verify(points, entry->second.serial, *entry->second.stored.data, guesses);
        if (!v.accepted) {
            rejection.reason = v.reason;
            r->rejected.push_back(rejection);
            continue;
        }
        if (loaded_match && v.min_sector_fraction < config_.map_edge.overlap) {
            std::ostringstream why;
            why.precision(2);
            why << "at the loaded map's edge: its local map explains " << v.min_sector_fraction
                << " of the keyframe's points towards " << int(std::lround(v.weakest_sector_deg))
                << " deg (below map_edge.overlap " << config_.map_edge.overlap << ")";
            rejection.reason = why.str();
            r->rejected.push_back(rejection);
            continue;
        }
        map::PoseGraphEdge e;
        e.from = match.node;
        e.to = node;
        e.kind = map::EdgeKind::kLoop;
        e.T_from_to = v.T_anchor_lidar * keyframe.T_anchor_lidar.inverse();
        const Eigen::Isometry3d D = predicted.inverse() * e.T_from_to;
        const double disagreement = D.translation().norm();
        const double disagreement_deg = Eigen::AngleAxisd(D.linear()).angle() * 180.0 / M_PI;
        // The odometry along which the graph's estimate can have drifted: from the nearest
        // places already joined by loops (a lap of a route is not 1 km of drift); a segment
        // break is unbounded drift.
        if (placed) {
            rejection.reason = inconsistency(e.from, e.to, disagreement, disagreement_deg);
            if (!rejection.reason.empty()) {
                r->rejected.push_back(rejection);
                continue;
            }
        }
        e.information = loop_information(config_.loop_edge);
        e.query_keyframe = r->index;
        e.match_keyframe = c.match;
        LoopClosure l;
        l.query_keyframe = r->index;
        l.match_keyframe = c.match;
        l.query_scan = keyframe.scan_index;
        l.match_scan = match.data.scan_index;
        l.query_session = session;
        l.match_session = match.session;
        l.query_segment = query_key.second;
        l.match_segment = match_key.second;
        l.across_break = same_session && !placed;
        l.from_node = e.from;
        l.to_node = e.to;
        l.T_from_to = e.T_from_to;
        l.T_match_query = match.data.T_anchor_lidar.inverse() * v.T_anchor_lidar;
        l.descriptor_distance = c.distance;
        l.descriptor_yaw = c.yaw;
        l.inliers = v.inliers;
        l.inlier_fraction = v.inlier_fraction;
        l.inlier_rms = v.inlier_rms;
        l.correction_translation = v.correction_translation;
        l.disagreement = disagreement;
        l.structure_points = v.structure_points;
        l.structure_inliers = v.structure_inliers;
        l.min_sector_fraction = v.min_sector_fraction;
        l.from_graph_guess = graph_guess && v.guess == 0;
        // Places joined already (by loops, as of the last optimisation) and a loop that only
        // confirms the graph: no optimisation due for it.
        l.agrees = segments_.root(match_key) == segments_.root(query_key) &&
                   disagreement <= config_.long_term.agree_translation &&
                   disagreement_deg <= config_.long_term.agree_rotation;
        // Two robots' parts not placed together: held until enough loops agree.
        std::vector<SessionJoins::Join> agreed;
        if (!same_session && !together && is_open(match.session) &&
            !joins_.confirm(segments_.root(match_key), segments_.root(query_key), e, l, graph_,
                            segments_, &agreed)) {
            rejection.reason = "held: the first loop between session " +
                               std::to_string(match.session) + "'s and session " +
                               std::to_string(session) +
                               "'s parts waits for another that agrees (session_join.loops)";
            r->rejected.push_back(rejection);
            continue;
        }
        // The held loops that agree with it go first (within max_loops_per_anchor_pair).
        std::vector<LoopClosure> joined;
        for (const SessionJoins::Join& j : agreed) {
            if (config_.max_loops_per_anchor_pair > 0 &&
                loops_between(j.edge.from, j.edge.to) >= config_.max_loops_per_anchor_pair)
                continue;
            if (graph_.add_edge(j.edge)) joined.push_back(j.loop);
        }
        if (!graph_.add_edge(e)) continue;
        // The first loop between two sessions' parts: the later part set where it says.
        if (!same_session && !together) align_parts(e);
        for (const LoopClosure& j : joined) {
            r->loops.push_back(j);
            loops_.push_back(j);
        }
        r->loops.push_back(l);
        loops_.push_back(l);
    }
}

double Mapper::drift_path(std::uint64_t from, std::uint64_t to) const {
    return drift_distance(graph_, from, to, [this](const map::PoseGraphEdge& o) {
        if (is_segment_break(o)) return std::numeric_limits<double>::infinity();
        // An edge made through a folded map joins nodes of other laps: its own length, not
        // their paths.
        if (folding_.relayed(o.from, o.to)) return o.T_from_to.translation().norm();
        return std::abs(chains_.path(o.to) - chains_.path(o.from));
    });
}

std::string Mapper::inconsistency(std::uint64_t from, std::uint64_t to, double disagreement,
                                  double disagreement_deg) const {
    const double path = drift_path(from, to);
    if (!std::isfinite(path)) return "";
    const LoopConsistencyConfig& lc = config_.loop_consistency;
    const double max_t = lc.translation + lc.translation_per_m * path;
    const double max_r = lc.rotation + lc.rotation_per_m * path;
    if (disagreement <= max_t && disagreement_deg <= max_r) return "";
    std::ostringstream why;
    why << "disagrees with the graph by " << disagreement << " m / " << disagreement_deg
        << " deg (limits " << max_t << " m / " << max_r << " deg after " << path
        << " m of odometry from places already joined)";
    return why.str();
}

void Mapper::align_parts(const map::PoseGraphEdge& loop) {
    const SegmentKey from_root = segments_.root(graph_, loop.from);
    const SegmentKey to_root = segments_.root(graph_, loop.to);
    if (from_root == to_root) return;
    std::vector<std::uint64_t> from_part, to_part;
    bool from_fixed = false, to_fixed = false;
    for (const map::PoseGraphNode& n : graph_.nodes()) {
        const SegmentKey r = segments_.root(graph_, n.id);
        if (r == from_root) {
            from_part.push_back(n.id);
            from_fixed = from_fixed || n.fixed;
        } else if (r == to_root) {
            to_part.push_back(n.id);
            to_fixed = to_fixed || n.fixed;
        }
    }
    // The later part moves (the map's first session stays), unless it holds a fixed node.
    bool move_to = from_root < to_root;
    if (move_to ? to_fixed : from_fixed) move_to = !move_to;
    if (move_to ? to_fixed : from_fixed) return;
    const Eigen::Isometry3d& T_from = graph_.find(loop.from)->T_world_anchor;
    const Eigen::Isometry3d& T_to = graph_.find(loop.to)->T_world_anchor;
    const Eigen::Isometry3d C = move_to ? T_from * loop.T_from_to * T_to.inverse()
                                        : T_to * loop.T_from_to.inverse() * T_from.inverse();
    for (const std::uint64_t id : move_to ? to_part : from_part)
        graph_.set_pose(id, C * graph_.find(id)->T_world_anchor);
}

int Mapper::loops_between(std::uint64_t a, std::uint64_t b) const {
    int n = 0;
    for (const map::PoseGraphEdge& e : graph_.edges()) {
        if (e.kind == map::EdgeKind::kLoop && e.active &&
            ((e.from == a && e.to == b) || (e.from == b && e.to == a)))
            ++n;
    }
    return n;
}

}  // namespace ltm::mapping
