#include "mapping/core/mapper.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include "mapping/core/drift_distance.hpp"

namespace ltm::mapping {
namespace {

const MapperConfig& checked(const MapperConfig& config) {
    common::throw_if(validate(config), "mapping");
    return config;
}

// A finite rigid transform (rotation orthonormal to 1e-3, as printed poses are), returned with
// its rotation re-orthonormalised; false otherwise.
bool rigid(const Eigen::Isometry3d& T, Eigen::Isometry3d* out) {
    if (!T.matrix().allFinite()) return false;
    const Eigen::Matrix3d R = T.linear();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-3 || R.determinant() <= 0.0) {
        return false;
    }
    *out = T;
    out->linear() = Eigen::Quaterniond(R).normalized().toRotationMatrix();
    return true;
}

// The loaded map's descriptors (a) must be made as the config's (b) are.
void require_same_descriptors(const places::ScanContextConfig& a,
                              const places::ScanContextConfig& b, const std::string& key) {
    if (a.kind != b.kind || a.rings != b.rings || a.sectors != b.sectors ||
        std::abs(a.max_range - b.max_range) > 1e-9 || std::abs(a.min_range - b.min_range) > 1e-9 ||
        std::abs(a.sensor_height - b.sensor_height) > 1e-9) {
        std::ostringstream e;
        e << "differs from the loaded map's descriptors (" << a.rings << " x " << a.sectors
          << ", kind " << int(a.kind) << ", max_range " << a.max_range << ", min_range "
          << a.min_range << ", sensor_height " << a.sensor_height << ")";
        throw common::ConfigError(key, e.str());
    }
}

}  // namespace

Mapper::Mapper(const MapperConfig& config)
    : config_(checked(config)),
      graph_(config.pose_graph),
      detector_(config.scan_context, config.loop_detection),
      verifier_(config.verification),
      joins_(config.session_join) {
    live_[session_];
}

Mapper::Mapper(const MapperConfig& config, const map::MapData& loaded, bool freeze_loaded)
    : Mapper(config) {
    require_same_descriptors(loaded.descriptor_config, config_.scan_context,
                             "mapping.scan_context");
    // A format-1 map has no localisation descriptors: its keyframes keep none, new ones get them.
    if (map::has_localisation_descriptors(loaded.localisation_descriptor_config)) {
        require_same_descriptors(loaded.localisation_descriptor_config,
                                 config_.localisation_descriptor,
                                 "mapping.localisation_descriptor");
    }
    std::uint32_t last_session = 0;
    for (map::PoseGraphNode n : loaded.nodes) {
        n.fixed = n.fixed || freeze_loaded;
        if (!graph_.add_node(n))
            throw common::IoError("loaded map",
                                  "node " + std::to_string(n.id) + " is invalid or repeated");
        chains_.set(n.session, n.local_map_id, n.id);
        next_node_ = std::max(next_node_, n.id + 1);
        last_session = std::max(last_session, n.session);
    }
    for (const map::PoseGraphEdge& e : loaded.edges) graph_.add_edge(e);
    std::map<std::pair<std::uint64_t, std::uint64_t>, bool> breaks;  // odometry edges (from, to)
    for (const map::PoseGraphEdge& e : graph_.edges()) {
        if (e.kind == map::EdgeKind::kOdometry) breaks[{e.from, e.to}] = is_segment_break(e);
    }
    for (const auto& [session, chain] : chains_.all()) {
        // The file keeps no segment numbers: the breaks in the odometry chain give them back.
        std::uint32_t segment = 0;
        std::uint64_t prev = 0;
        for (const auto& [local_map_id, id] : chain) {
            if (local_map_id != chain.begin()->first) {
                const auto b = breaks.find({prev, id});
                if (b != breaks.end() && b->second) ++segment;
            }
            segments_.set(id, segment, true);
            prev = id;
            chains_.set_path(view(), session, local_map_id);
        }
    }
    for (const std::shared_ptr<const map::StoredKeyframe>& k : loaded.keyframes) {
        if (!k || !detector_.add_searchable(k->descriptor)) continue;
        keyframes_.push_back(k);
    }
    for (const map::StoredLocalMap& m : loaded.local_maps) {
        if (m.data && graph_.find(m.node)) maps_[m.node] = MapEntry{m, next_serial_++};
    }
    session_ = loaded.nodes.empty() ? 0 : last_session + 1;
    revision_ = loaded.revision;
    past_sessions_ = loaded.sessions;
    if (past_sessions_.empty() && !loaded.nodes.empty()) {
        // A map of format 1 or 2 records no sessions: what its graph and keyframes say (no
        // merging existed then, so nothing was updated).
        std::map<std::uint32_t, map::SessionRecord> known;
        for (const map::PoseGraphNode& n : loaded.nodes) {
            known[n.session].id = n.session;
            ++known[n.session].local_maps_added;
        }
        std::map<std::uint32_t, bool> stamped;
        for (const std::shared_ptr<const map::StoredKeyframe>& k : loaded.keyframes) {
            if (!k || !known.count(k->session)) continue;
            map::SessionRecord& r = known[k->session];
            r.first_stamp =
                stamped[k->session] ? std::min(r.first_stamp, k->data.stamp) : k->data.stamp;
            r.last_stamp =
                stamped[k->session] ? std::max(r.last_stamp, k->data.stamp) : k->data.stamp;
            stamped[k->session] = true;
        }
        for (const auto& [id, r] : known) past_sessions_.push_back(r);
    }
    session_ = std::max(session_, past_sessions_.empty() ? 0u : past_sessions_.back().id + 1);
    live_.clear();
    live_[session_];
    segments_.update_placement(graph_);
}

std::uint32_t Mapper::open_session(const std::string& name) {
    // A name is one word (the map's manifest lists it on the session's line).
    std::string robot = name;
    for (char& c : robot) {
        if (std::isspace(static_cast<unsigned char>(c))) c = '_';
    }
    for (const auto& [id, live] : live_) {
        if (live.robot == robot && !robot.empty()) return id;
    }
    Live& first = live_.at(session_);
    if (first.robot.empty() && first.keyframes_seen == 0 && !chains_.has(session_)) {
        first.robot = robot;
        return session_;
    }
    std::uint32_t id = live_.rbegin()->first;
    if (!chains_.all().empty()) id = std::max(id, chains_.all().rbegin()->first);
    live_[id + 1].robot = robot;
    return id + 1;
}

std::vector<std::uint32_t> Mapper::open_sessions() const {
    std::vector<std::uint32_t> out;
    for (const auto& [id, live] : live_) out.push_back(id);
    return out;
}

std::string Mapper::robot(std::uint32_t session) const {
    const auto it = live_.find(session);
    if (it != live_.end()) return it->second.robot;
    for (const map::SessionRecord& r : past_sessions_) {
        if (r.id == session) return r.robot;
    }
    return "";
}

std::optional<std::uint64_t> Mapper::node_of(std::uint64_t local_map_id) const {
    return node_of(local_map_id, session_);
}

std::optional<std::uint64_t> Mapper::node_of(std::uint64_t local_map_id,
                                             std::uint32_t session) const {
    return chains_.node_of(session, local_map_id);
}

LocalMapResult Mapper::add_local_map(const common::LocalMapData& map) {
    return add_local_map(map, session_);
}

LocalMapResult Mapper::add_local_map(std::shared_ptr<const common::LocalMapData> map) {
    return add_local_map(std::move(map), session_);
}

LocalMapResult Mapper::add_local_map(const common::LocalMapData& map, std::uint32_t session) {
    return add_local_map(std::make_shared<const common::LocalMapData>(map), session);
}

LocalMapResult Mapper::add_local_map(std::shared_ptr<const common::LocalMapData> map,
                                     std::uint32_t session) {
    LocalMapResult r;
    if (!is_open(session)) {
        r.message = "session " + std::to_string(session) + " is not open";
        return r;
    }
    if (!map) {
        r.message = "no local map";
        return r;
    }
    Eigen::Isometry3d T_odom_anchor, T_anchor_grid;
    if (!rigid(map->T_odom_anchor, &T_odom_anchor) || !rigid(map->T_anchor_grid, &T_anchor_grid)) {
        r.message = "local map " + std::to_string(map->id) +
                    ": anchor or grid pose is not a finite rigid transform";
        return r;
    }
    if (!T_odom_anchor.isApprox(map->T_odom_anchor, 0.0) ||
        !T_anchor_grid.isApprox(map->T_anchor_grid, 0.0)) {
        auto copy = std::make_shared<common::LocalMapData>(*map);  // stored re-orthonormalised
        copy->T_odom_anchor = T_odom_anchor;
        copy->T_anchor_grid = T_anchor_grid;
        map = std::move(copy);
    }
    if (!(map->voxel_size > 0.0f) || !std::isfinite(map->voxel_size)) {
        r.message = "local map " + std::to_string(map->id) + ": voxel size must be > 0";
        return r;
    }
    if (const Folded* f = folding_.find(session, map->id)) {
        r.node = f->node;
        r.merged = true;
        r.message = "local map " + std::to_string(map->id) +
                    ": already folded into the local map of node " + std::to_string(f->node);
        return r;
    }
    r.node = ensure_node(session, map->id, map->T_odom_anchor, map->segment);
    const auto it = maps_.find(r.node);
    if (it != maps_.end() && meta(it->second).revision > map->revision) {
        r.message = "local map " + std::to_string(map->id) + ": revision " +
                    std::to_string(map->revision) + " is older than the stored " +
                    std::to_string(meta(it->second).revision);
        return r;
    }
    // What maintenance found gone stays gone in newer snapshots (on placed parts only: an
    // unplaced part's world poses are not where the cells are).
    if (!removed_.empty() && on_reference_part(r.node)) {
        std::size_t removed = 0;
        if (auto cleared = without_removed(*map, graph_.find(r.node)->T_world_anchor, &removed)) {
            map = std::move(cleared);
            removed_voxels_ += removed;
        }
    }
    MapEntry& e = maps_[r.node];
    e.stored.node = r.node;
    e.stored.session = session;
    e.stored.data = std::move(map);
    e.stored.paged.reset();  // a newer snapshot replaces a paged-out one
    e.header.reset();
    e.unavailable = false;
    e.serial = next_serial_++;
    r.added = true;
    if (e.stored.data->finished) {
        if (const std::optional<std::uint64_t> into = try_fold(r.node)) {
            r.node = *into;
            r.merged = true;
        }
    }
    return r;
}

KeyframeResult Mapper::add_keyframe(const common::KeyframeData& input) {
    return add_keyframe(input, session_);
}

KeyframeResult Mapper::add_keyframe(const common::KeyframeData& input, std::uint32_t session) {
    return add_keyframe(input, session, KeyframeDescriptors{});
}

KeyframeResult Mapper::add_keyframe(const common::KeyframeData& input, std::uint32_t session,
                                    const KeyframeDescriptors& given) {
    KeyframeResult r;
    const auto live = live_.find(session);
    if (live == live_.end()) {
        r.message = "keyframe " + std::to_string(input.id) + ": session " +
                    std::to_string(session) + " is not open";
        return r;
    }
    Live& own = live->second;
    common::KeyframeData keyframe;  // the poses re-orthonormalised; the points are not copied
    if (!rigid(input.T_odom_lidar, &keyframe.T_odom_lidar) ||
        !rigid(input.T_anchor_lidar, &keyframe.T_anchor_lidar)) {
        r.message =
            "keyframe " + std::to_string(input.id) + ": pose is not a finite rigid transform";
        return r;
    }
    keyframe.id = input.id;
    keyframe.scan_index = input.scan_index;
    keyframe.local_map_id = input.local_map_id;
    keyframe.stamp = input.stamp;
    if (!std::isfinite(keyframe.stamp)) {
        r.message = "keyframe " + std::to_string(keyframe.id) + ": stamp is not finite";
        return r;
    }
    const Eigen::Isometry3d T_odom_anchor =
        keyframe.T_odom_lidar * keyframe.T_anchor_lidar.inverse();
    const std::uint64_t node =
        ensure_node(session, keyframe.local_map_id, T_odom_anchor, input.segment);
    // A keyframe of a local map folded already: its pose in the node it went into.
    if (const Folded* f = folding_.find(session, keyframe.local_map_id))
        keyframe.T_anchor_lidar = f->T_node_anchor * keyframe.T_anchor_lidar;
    auto stored = std::make_shared<map::StoredKeyframe>();
    stored->session = session;
    stored->node = node;
    const places::ScanContext* loop_descriptor = usable(given.loop, config_.scan_context);
    stored->descriptor = loop_descriptor
                             ? *loop_descriptor
                             : places::make_scan_context(input.points, config_.scan_context);
    std::vector<LoopCandidate> candidates;
    if (!(config_.loop_closure
              ? detector_.search(stored->descriptor, session, keyframe.stamp, &candidates)
              : detector_.add_searchable(stored->descriptor))) {
        r.message = "keyframe " + std::to_string(keyframe.id) + ": descriptor has the wrong shape";
        return r;
    }
    // At a mapped place (long_term): not stored again, the stored keyframe there stands for it.
    const std::optional<std::uint32_t> standing =
        config_.loop_closure
            ? stand_in(session, keyframe.local_map_id, node,
                       graph_.find(node)->T_world_anchor * keyframe.T_anchor_lidar, keyframe.stamp)
            : std::nullopt;
    if (config_.loop_closure && !standing)
        detector_.keep(stored->descriptor, session, keyframe.stamp);
    r.added = true;
    r.kept = !standing;
    r.index = standing ? *standing : std::uint32_t(keyframes_.size());
    r.candidates = candidates.size();
    if (own.keyframes_seen == 0) own.record.first_stamp = own.record.last_stamp = keyframe.stamp;
    ++own.keyframes_seen;
    own.position = (graph_.find(node)->T_world_anchor * keyframe.T_anchor_lidar).translation();
    own.record.first_stamp = std::min(own.record.first_stamp, keyframe.stamp);
    own.record.last_stamp = std::max(own.record.last_stamp, keyframe.stamp);
    if (own.cooldown > 0) {
        --own.cooldown;
    } else {
        add_place_candidates(session, node, keyframe.T_anchor_lidar, stored->descriptor,
                             &candidates);
        if (!candidates.empty()) {
            r.verified = true;
            verify(session, keyframe, input.points, node, candidates, &r);
            if (!r.loops.empty()) own.cooldown = config_.loop_cooldown_keyframes;
            for (const LoopClosure& l : r.loops) due_loops_ += l.agrees ? 0 : 1;
        }
    }
    if (standing) return r;
    const places::ScanContext* localisation =
        usable(given.localisation, config_.localisation_descriptor);
    stored->localisation_descriptor =
        localisation ? *localisation
                     : places::make_scan_context(input.points, config_.localisation_descriptor);
    stored->data.id = keyframe.id;
    stored->data.scan_index = keyframe.scan_index;
    stored->data.local_map_id = keyframe.local_map_id;
    stored->data.stamp = keyframe.stamp;
    stored->data.T_odom_lidar = keyframe.T_odom_lidar;
    stored->data.T_anchor_lidar = keyframe.T_anchor_lidar;
    if (config_.keep_keyframe_points) stored->data.points = input.points;
    keyframes_.push_back(std::move(stored));
    return r;
}

OptimisationSummary Mapper::optimise() {
    const OptimisationSummary s = graph_.optimise();
    if (s.solved) {
        due_loops_ = 0;
        ++revision_;
        segments_.update_placement(graph_);
        place_unjoined_segments();
    }
    return s;
}

bool Mapper::apply(const PoseGraph& optimised, const OptimisationSummary& summary) {
    if (!summary.solved) return false;
    due_loops_ = 0;
    // Nodes folded since the snapshot are gone: set_pose leaves them out.
    for (const map::PoseGraphNode& n : optimised.nodes()) graph_.set_pose(n.id, n.T_world_anchor);
    // Loop flags: edges are matched by their ends, kind and keyframes.
    using Key = std::tuple<std::uint64_t, std::uint64_t, int, std::uint64_t, std::uint64_t>;
    std::map<Key, const map::PoseGraphEdge*> solved;
    for (const map::PoseGraphEdge& e : optimised.edges()) {
        solved[Key(e.from, e.to, int(e.kind), e.query_keyframe, e.match_keyframe)] = &e;
    }
    PoseGraph updated(graph_.config());
    for (const map::PoseGraphNode& n : graph_.nodes()) updated.add_node(n);
    for (map::PoseGraphEdge e : graph_.edges()) {
        const auto it =
            solved.find(Key(e.from, e.to, int(e.kind), e.query_keyframe, e.match_keyframe));
        if (it != solved.end()) {
            e.active = it->second->active;
            e.error_translation = it->second->error_translation;
            e.error_rotation = it->second->error_rotation;
        }
        updated.add_edge(e);
    }
    graph_ = std::move(updated);
    segments_.update_placement(graph_);
    // Nodes added since the snapshot follow their predecessor's correction.
    for (const auto& [session, chain] : chains_.all()) {
        for (const auto& [local_map_id, id] : chain) {
            if (optimised.find(id) || folding_.find(session, local_map_id)) continue;
            const map::PoseGraphNode* n = graph_.find(id);
            graph_.set_pose(
                id, chains_.predicted_world(view(), session, local_map_id, n->T_odom_anchor));
        }
    }
    place_unjoined_segments();
    ++revision_;
    return true;
}

}  // namespace ltm::mapping
