// The Mapper on one map over many laps and sessions (see mapper.hpp, LongTermConfig): finished
// local maps of mapped places folded into the existing ones, the graph kept consistent (edges and
// keyframes of a folded map moved to the node it went into), keyframes at mapped places not
// stored again, and the sessions that built the map. Split from mapper.cpp: one concept a file.
#include <algorithm>
#include <cmath>
#include <limits>

#include "mapping/core/local_map_merge.hpp"
#include "mapping/core/mapper.hpp"

namespace ltm::mapping {

bool Mapper::tied_by_loop(std::uint64_t node) const {
    for (const map::PoseGraphEdge& e : graph_.edges()) {
        if (e.kind == map::EdgeKind::kLoop && e.active && (e.from == node || e.to == node))
            return true;
    }
    return false;
}

std::optional<std::uint32_t> Mapper::stand_in(std::uint32_t session, std::uint64_t local_map_id,
                                              std::uint64_t node, const Eigen::Isometry3d& T_world,
                                              double stamp) const {
    const LongTermConfig& lt = config_.long_term;
    if (!lt.merge || keyframes_.empty()) return std::nullopt;
    // The keyframe's world pose must be tied to the map: its local map has a loop, or the map
    // before it in the chain was folded into an earlier one or has a loop (then only one local
    // map of odometry lies between): never on odometry drift alone.
    bool tied = tied_by_loop(node);
    if (!tied) {
        const OdometryChains::Chain& chain = *chains_.chain(session);
        const auto it = chain.find(local_map_id);
        if (it != chain.end() && it != chain.begin()) {
            const auto prev = std::prev(it);
            tied = folding_.find(session, prev->first) || tied_by_loop(prev->second);
        }
    }
    if (!tied) return std::nullopt;
    const double max_angle = lt.keyframe_angle * M_PI / 180.0;
    const LoopDetectorConfig& recent = config_.loop_detection;
    std::optional<std::uint32_t> best;
    double best_d = lt.keyframe_distance;
    for (std::uint32_t i = 0; i < keyframes_.size(); ++i) {
        const map::StoredKeyframe& k = *keyframes_[i];
        // An earlier lap's or session's keyframe, not one of this stretch of the drive (what the
        // loop detection calls recent).
        if (k.node == node) continue;
        if (k.session == session &&
            (keyframes_.size() - i < std::size_t(recent.exclude_recent_keyframes) ||
             !(stamp - k.data.stamp >= recent.exclude_recent_seconds)))
            continue;
        const map::PoseGraphNode* n = graph_.find(k.node);
        if (!n) continue;
        const Eigen::Isometry3d T_k = n->T_world_anchor * k.data.T_anchor_lidar;
        const double d = (T_k.translation() - T_world.translation()).norm();
        if (d > best_d) continue;
        if (Eigen::AngleAxisd(T_k.linear().transpose() * T_world.linear()).angle() > max_angle)
            continue;
        best_d = d;
        best = i;
    }
    return best;
}

std::optional<std::uint64_t> Mapper::try_fold(std::uint64_t n) {
    const LongTermConfig& lt = config_.long_term;
    const map::PoseGraphNode* node = graph_.find(n);
    const auto entry = maps_.find(n);
    if (!lt.merge || !node || !is_open(node->session) || node->fixed || entry == maps_.end())
        return std::nullopt;
    const std::uint32_t session = node->session;
    // Tied to the map by a verified loop, and the graph settled (no optimisation due).
    if (due_loops_ > 0 || !tied_by_loop(n)) return std::nullopt;
    const SegmentKey root = segments_.root(graph_, n);
    const common::LocalMapData& data = *entry->second.stored.data;
    const double path = chains_.path(n);
    std::optional<std::uint64_t> best;
    double best_d = lt.merge_distance;
    for (const auto& [id, e] : maps_) {
        const map::PoseGraphNode* other = graph_.find(id);
        if (id == n || !other || meta(e).voxel_size != data.voxel_size) continue;
        // Not a map still being built by an open session, this one or another robot's (its next
        // snapshot would replace the merge); an earlier session's map gets no newer snapshot,
        // finished or not.
        if (is_open(other->session) && !meta(e).finished) continue;
        // An earlier lap: not a neighbour on this drive (anchors of consecutive maps can be
        // closer than merge_distance after a turn).
        if (other->session == session) {
            if (!chains_.has_path(id) || path - chains_.path(id) < 4.0 * lt.merge_distance)
                continue;
        }
        // Placed together by loops: never across parts no loop has joined.
        if (segments_.root(graph_, id) != root) continue;
        const double d =
            (other->T_world_anchor.translation() - node->T_world_anchor.translation()).norm();
        if (d <= best_d) {
            best_d = d;
            best = id;
        }
    }
    if (!best) return std::nullopt;
    if (!page_in(*best, maps_.at(*best))) return std::nullopt;  // unavailable: kept apart
    const Eigen::Isometry3d T_graph =
        graph_.find(*best)->T_world_anchor.inverse() * node->T_world_anchor;
    fold(n, *best, registered_fold(n, *best, T_graph).value_or(T_graph));
    return best;
}

std::optional<Eigen::Isometry3d> Mapper::registered_fold(std::uint64_t n, std::uint64_t into,
                                                         const Eigen::Isometry3d& T_graph) {
    const LongTermConfig& lt = config_.long_term;
    if (!lt.register_fold) return std::nullopt;
    // Only into an earlier session's map (another day's, which no open session's optimisation
    // moves): the folded map is put on its surfaces. Two maps of open sessions (one day's laps,
    // robots mapping at once) are both placed by the same optimisation, whose estimate of where
    // the one lies in the other is already the consensus of the loops registering the folded
    // map's keyframes to the other; one more registration of the map's voxels overrode it
    // (site_loop day 0: 6 folds, median 4.1 cm off the graph, the final keyframes 0.065 -> 0.087 m
    // rmse).
    if (is_open(graph_.find(into)->session)) return std::nullopt;
    // The folded map's surfaces (its voxels with a normal) in its anchor frame, registered to the
    // map they go into from the graph's estimate.
    const common::LocalMapData& add = *maps_.at(n).stored.data;
    std::vector<Eigen::Vector3f> points;
    points.reserve(add.voxels.size());
    const Eigen::Isometry3f T_anchor_grid = add.T_anchor_grid.cast<float>();
    for (const common::VoxelData& v : add.voxels) {
        if (v.normal.squaredNorm() > 0.0f) points.push_back(T_anchor_grid * v.centre);
    }
    const MapEntry& target = maps_.at(into);
    const registration::LoopVerification r =
        verifier_.verify(points, target.serial, *target.stored.data, T_graph);
    ++fold_stats_.tried;
    if (!r.accepted) return std::nullopt;
    const Eigen::Isometry3d d = T_graph.inverse() * r.T_anchor_lidar;
    const double dt = d.translation().norm();
    const double dr = Eigen::AngleAxisd(d.linear()).angle() * 180.0 / M_PI;
    // Larger than the graph can be off between places loops joined: another fit, not this one.
    if (dt > lt.fold_max_correction || dr > lt.fold_max_correction_rotation) return std::nullopt;
    ++fold_stats_.registered;
    fold_stats_.corrections.push_back(dt);
    return r.T_anchor_lidar;
}

void Mapper::fold(std::uint64_t n, std::uint64_t into, const Eigen::Isometry3d& T_into_n) {
    const map::PoseGraphNode folded_node = *graph_.find(n);
    const Eigen::Isometry3d T_n_into = T_into_n.inverse();

    // The voxels.
    MapEntry& e = maps_.at(into);
    auto merged = std::make_shared<common::LocalMapData>(merge_local_maps(
        *e.stored.data, *maps_.at(n).stored.data, T_into_n,
        std::size_t(config_.long_term.max_observation_times), config_.long_term.same_surface,
        nullptr, config_.long_term.beside_surface));
    forgotten_voxels_ += forget_unseen_voxels(merged.get(), config_.long_term.forget_after_visits,
                                              config_.long_term.visit_gap);
    e.stored.data = std::move(merged);
    e.serial = next_serial_++;

    // The graph without the node: its edges name `into`, measured from its anchor.
    graph_ = folding_.without(graph_, n, into, T_into_n, config_.max_loops_per_anchor_pair);

    // Keyframes of the folded map: in the node it went into.
    for (std::shared_ptr<const map::StoredKeyframe>& k : keyframes_) {
        if (k->node != n) continue;
        auto copy = std::make_shared<map::StoredKeyframe>(*k);
        copy->node = into;
        copy->data.T_anchor_lidar = T_into_n * k->data.T_anchor_lidar;
        k = std::move(copy);
    }
    for (LoopClosure& l : loops_) {
        if (l.from_node == n) {
            l.from_node = into;
            l.T_from_to = T_into_n * l.T_from_to;
        }
        if (l.to_node == n) {
            l.to_node = into;
            l.T_from_to = l.T_from_to * T_n_into;
        }
    }

    // The chain goes on from `into`: the local map id names it, with its own anchor there.
    Folded f;
    f.node = into;
    f.T_node_anchor = T_into_n;
    f.T_odom_anchor = folded_node.T_odom_anchor;
    f.segment = segment_of(n);
    f.path = chains_.path(n);
    folding_.record(folded_node.session, folded_node.local_map_id, f);
    chains_.set(folded_node.session, folded_node.local_map_id, into);
    // Maps folded into n earlier (a map still being built when a later one was folded into it)
    // follow it: no map, keyframe or chain may name a node that left the graph.
    for (const auto& [session, local_map_id] : folding_.retarget(n, into, T_into_n))
        chains_.set(session, local_map_id, into);
    maps_.erase(n);
    segments_.forget(n);
    chains_.forget_path(n);
}

std::vector<map::SessionRecord> Mapper::sessions() const {
    std::vector<map::SessionRecord> out = past_sessions_;
    for (const auto& [session, live] : live_) {
        map::SessionRecord r = live.record;
        r.id = session;
        r.robot = live.robot;
        std::set<std::uint64_t> updated;
        if (const OdometryChains::Chain* chain = chains_.chain(session)) {
            for (const auto& [local_map_id, node] : *chain) {
                if (const Folded* f = folding_.find(session, local_map_id)) {
                    // A map folded into another map of this session counts as added.
                    const map::PoseGraphNode* into = graph_.find(f->node);
                    if (into && into->session != session) updated.insert(f->node);
                } else if (maps_.count(node)) {
                    ++r.local_maps_added;
                }
            }
        }
        r.local_maps_updated = updated.size();
        if (live.keyframes_seen > 0 || r.local_maps_added > 0 || r.local_maps_updated > 0)
            out.push_back(r);
    }
    return out;
}

}  // namespace ltm::mapping
