#pragma once
// The hierarchical SLAM back end (METHOD.md section 3, Eq. 9-10): a short facade over the modules
//   keyframe -> Scan Context -> loop candidates (LoopDetector) -> geometric verification against
//   the candidate's local map (LoopVerifier; from the graph's estimate within a session, then
//   from the descriptor's guess) -> loop edge in the PoseGraph;
//   local map -> graph node (its anchor) with an odometry edge to the previous one;
//   optimise() on demand -> corrected anchors, hence corrected poses and the global map.
// Odometry segments (common::LocalMapData::segment): when the odometry lost track and restarted,
// the first map of the new segment is joined to the one before by a very weak edge
// (segment_break_information()), not by odometry. Until an optimised loop joins the segment to the
// map, its poses are the odometry's best estimate across the break, a loop candidate between it
// and the rest of the session is verified from the descriptor's guess only and judged by the
// verification alone (no odometry bound across a break); once joined, the optimisation has put
// the segment, and every map after it, in place.
// Synchronous, no threads, no I/O. An adapter may run the optimisation elsewhere: take
// graph_snapshot(), call PoseGraph::optimise() on it on any thread, then apply() the result.
//
// Long-term (LongTermConfig, mapper_long_term.cpp): the map grows with the site, not with the
// distance driven. A finished local map of the current session at a place an earlier lap or
// session mapped (its anchor within long_term.merge_distance of that map's, by the graph) is folded
// into that map (local_map_merge.hpp) when a verified loop ties it to the map and no optimisation
// is due: its node leaves the graph, its edges and keyframes name the existing node (keyframe
// poses re-expressed in its anchor), and the odometry chain goes on from the existing node (the
// local map id stays known: T_world_odom, node_of, T_world_lidar answer for it). A keyframe near a
// stored keyframe of an earlier lap or session is searched and verified but not stored. A loop
// between places already joined that agrees with the graph does not make an optimisation due.
//
// Several robots at once (open_session): each robot's session has its own odometry chain, folded
// maps, loop cool-down, segments and record; the calls without a session mean the first (default)
// session, which the first open_session() takes while it is unused. Loop detection searches every
// other session's keyframes as they arrive (a robot at a place another one mapped a minute ago,
// either way). A session that no loop ties to the map yet is where its own odometry puts it (its
// own connected part of the graph, like a segment across a break that no loop joined): candidates
// between it and another session are verified from the descriptor's guess and judged by the
// verification alone, and held until session_join.loops of them agree (a repetitive site can fool
// one verification). The loop that joins two open sessions' parts sets the part that holds no
// fixed node (the later one) rigidly where it says, and the optimisation puts it in place; from
// then on, loops between open sessions placed together start from the graph's estimate and are
// bounded by the odometry between them, as within one session.
//
// Parts, each owning its state (the Mapper holds the graph, local maps, keyframes and loops, and
// hands them to the parts' calls): OdometryChains (each session's chain of local maps as nodes,
// odometry edges, paths), Segments (each node's odometry segment, the parts loops placed together),
// LongTermFolding (where folded local maps went), SessionJoins (loops held between sessions).
//
// Frames: every odometry pose belongs to the local map it was registered in; its world pose is
// T_world_anchor * T_odom_anchor^-1 * T_odom_lidar. Voxels never move inside their local map.
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/core/io_error.hpp"
#include "common/core/local_map_data.hpp"
#include "common/core/ply_io.hpp"
#include "map/core/map_data.hpp"
#include "map/core/map_store.hpp"
#include "mapping/core/keyframe_digest.hpp"
#include "mapping/core/long_term_folding.hpp"
#include "mapping/core/loop_detector.hpp"
#include "mapping/core/mapper_config.hpp"
#include "mapping/core/mapper_results.hpp"
#include "mapping/core/odometry_chains.hpp"
#include "mapping/core/pose_graph.hpp"
#include "mapping/core/removed_cells.hpp"
#include "mapping/core/segments.hpp"
#include "mapping/core/session_joins.hpp"
#include "registration/core/loop_verifier.hpp"

namespace ltm::mapping {

class Mapper {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    explicit Mapper(const MapperConfig& config);
    // Continues a loaded map in a new session: its keyframes are searchable at once and, with
    // `freeze_loaded`, its anchors are held fixed. Throws common::ConfigError (key
    // mapping.scan_context, mapping.localisation_descriptor) when the map's descriptors are not
    // made as config.scan_context's, config.localisation_descriptor's are (a map without
    // localisation descriptors, format 1, is accepted: its keyframes keep none, the new ones get
    // them), and common::IoError when its graph holds an invalid or repeated node.
    Mapper(const MapperConfig& config, const map::MapData& loaded, bool freeze_loaded = true);

    const MapperConfig& config() const { return config_; }
    // The default session (the one the calls without a session mean).
    std::uint32_t session() const { return session_; }
    // A new session for robot `robot` (another robot mapping the same site at the same time); the
    // default session when it has no robot yet and nothing was added to it. Its id.
    std::uint32_t open_session(const std::string& robot);
    // The sessions open in this Mapper (the default one first), and the robot of each.
    std::vector<std::uint32_t> open_sessions() const;
    bool is_open(std::uint32_t session) const { return live_.count(session) > 0; }
    std::string robot(std::uint32_t session) const;
    // Where an open session stands (joined to the map by loops, or not yet).
    SessionStatus session_status(std::uint32_t session) const;
    // The parts of the map that loops have placed together, as of the last optimisation: 1 when
    // every session and segment is joined (the graph's connected parts also count the weak edges
    // across odometry breaks).
    std::size_t placed_parts() const;
    std::uint64_t revision() const { return revision_; }

    // A local map, or a newer snapshot of one (same id, higher or equal revision). Never throws.
    LocalMapResult add_local_map(const common::LocalMapData& map);
    LocalMapResult add_local_map(std::shared_ptr<const common::LocalMapData> map);
    // A keyframe: loop detection and verification; accepted loops become graph edges.
    KeyframeResult add_keyframe(const common::KeyframeData& keyframe);
    // The same for an open session (a session that is not open: not added, the message says so).
    LocalMapResult add_local_map(const common::LocalMapData& map, std::uint32_t session);
    LocalMapResult add_local_map(std::shared_ptr<const common::LocalMapData> map,
                                 std::uint32_t session);
    KeyframeResult add_keyframe(const common::KeyframeData& keyframe, std::uint32_t session);
    // The same with the keyframe's descriptors made elsewhere from its whole scan (a keyframe
    // digested on the robot, keyframe_digest.hpp: its points are the verification's sample).
    // Each descriptor made as this Mapper makes it is used as it is; one made otherwise (or none)
    // is made here from the keyframe's points.
    KeyframeResult add_keyframe(const common::KeyframeData& keyframe, std::uint32_t session,
                                const KeyframeDescriptors& given);

    // Optimises the graph now; the revision increases when it succeeds.
    OptimisationSummary optimise();
    // The same in two halves, for an optimisation run off this object's thread.
    PoseGraph graph_snapshot() const { return graph_; }
    // Takes the optimised poses and loop flags of a snapshot; nodes added since are carried along
    // by their odometry. False (nothing changed) when the summary says it was not solved.
    bool apply(const PoseGraph& optimised, const OptimisationSummary& summary);

    const PoseGraph& graph() const { return graph_; }
    const std::vector<LoopClosure>& loops() const { return loops_; }
    const std::vector<std::shared_ptr<const map::StoredKeyframe>>& keyframes() const {
        return keyframes_;
    }
    // The graph node of a local map of the current session.
    std::optional<std::uint64_t> node_of(std::uint64_t local_map_id) const;
    // World pose of an odometry pose registered in local map `local_map_id` (current session).
    std::optional<Eigen::Isometry3d> T_world_lidar(std::uint64_t local_map_id,
                                                   const Eigen::Isometry3d& T_odom_lidar) const;
    // The correction of that local map's odometry frame: T_world_odom.
    std::optional<Eigen::Isometry3d> T_world_odom(std::uint64_t local_map_id) const;
    // The same three for a local map of session `session` (any session with nodes).
    std::optional<std::uint64_t> node_of(std::uint64_t local_map_id, std::uint32_t session) const;
    std::optional<Eigen::Isometry3d> T_world_lidar(std::uint64_t local_map_id,
                                                   const Eigen::Isometry3d& T_odom_lidar,
                                                   std::uint32_t session) const;
    std::optional<Eigen::Isometry3d> T_world_odom(std::uint64_t local_map_id,
                                                  std::uint32_t session) const;
    // World pose of keyframe i.
    Eigen::Isometry3d keyframe_pose(std::uint32_t index) const;
    // The odometry segment of a graph node (0 for an unknown node). A node made by a keyframe
    // before its local map arrived takes the segment of the map before it until then.
    std::uint32_t segment_of(std::uint64_t node) const;
    // The current session's segments, in order.
    std::vector<SegmentStatus> segments() const;
    // An open session's segments, in order (none for a session that is not open).
    std::vector<SegmentStatus> segments(std::uint32_t session) const;

    // A localisation fix (MapFixConfig): keyframe `keyframe_index` of `session`, at T_anchor_lidar
    // in local map `local_map_id`, lies at T_world_lidar in the loaded map's frame, as a
    // localisation registered to that map found. An edge from the nearest loaded keyframe's node;
    // the first fix of a part (the session, or a segment after a break) places it. Never throws.
    MapFixResult add_map_fix(std::uint32_t session, std::uint64_t local_map_id,
                             const Eigen::Isometry3d& T_anchor_lidar,
                             const Eigen::Isometry3d& T_world_lidar, std::uint32_t keyframe_index);
    std::size_t map_fixes() const { return map_fixes_; }
    // A localisation on the loaded map sends fixes: it alone places a part on the loaded map (a
    // loop from a part not placed yet to the loaded map is held), and loops from a placed part to
    // the loaded map are checked against the graph like loops within a session.
    void expect_map_fixes(bool on) { fixes_expected_ = on; }

    // What map maintenance found gone (mapper_map_edits.cpp): the cells of edge `cell_size` (world
    // frame) holding `centres` are cleared of voxels in every local map (a voxel goes when its
    // centre lies in such a cell, within half a cell of one, or within half its own edge of a
    // cell centre), now and in the local maps that
    // arrive later in this Mapper's life (snapshots of a map still being built hold them again).
    // `vanished`: the cells of each vanished segment (among `centres`); those of a segment of at
    // least map_edits.surface_min_cells also take the voxels whose own surface they lie on within
    // one voxel edge (MapEditConfig). The local maps' voxels removed.
    std::size_t remove_cells(const std::vector<Eigen::Vector3f>& centres, float cell_size,
                             const std::vector<std::vector<Eigen::Vector3f>>& vanished = {});
    // The same in steps (issue 28: a pass's edits spread, not a burst on the mapping's thread):
    // records the cells now (local maps that arrive later are cleared of them at once) and lists
    // the local maps near them, which clear_removed_step() clears one at a time (true while more
    // wait; *removed: its voxels removed). The result is remove_cells' once all steps ran.
    // Local maps waiting to be cleared.
    std::size_t remove_cells_in_steps(
        const std::vector<Eigen::Vector3f>& centres, float cell_size,
        const std::vector<std::vector<Eigen::Vector3f>>& vanished = {});
    bool clear_removed_step(std::size_t* removed = nullptr);
    std::size_t removal_waiting() const { return removal_waiting_.size(); }
    // New objects found there: their cells are no longer cleared in maps that arrive later.
    void keep_cells(const std::vector<Eigen::Vector3f>& centres, float cell_size);
    std::size_t removed_voxels() const { return removed_voxels_; }
    // Voxels folded local maps forgot (LongTermConfig::forget_after_visits), since the start.
    std::size_t forgotten_voxels() const { return forgotten_voxels_; }
    // Folds since the start: registrations tried, those used, and their corrections to the
    // graph's estimate [m] (LongTermConfig::register_fold).
    struct FoldStats {
        std::size_t tried = 0, registered = 0;
        std::vector<double> corrections;
    };
    const FoldStats& fold_stats() const { return fold_stats_; }

    // Paging (PagingConfig, mapper_paging.cpp). `loader` reads a paged-out local map's file back
    // (map::load_local_map from the directory the saves go to) and throws on failure; without
    // one (a plain mapping run, tests) nothing is paged.
    using LocalMapLoader =
        std::function<std::shared_ptr<const common::LocalMapData>(const map::LocalMapFile&)>;
    void set_local_map_loader(LocalMapLoader loader) { loader_ = std::move(loader); }
    // Pages out the local maps far from every open session's newest keyframe whose data is the
    // one the last save wrote (`written`: map::MapWriter::written_local_maps). How many went.
    std::size_t page_out(
        const std::unordered_map<std::uint64_t, map::MapWriter::WrittenLocalMap>& written);
    std::size_t paged_out() const;                      // local maps on disk only, now
    std::size_t paged_in() const { return paged_in_; }  // loads back so far
    // The loads that failed since the last call, one line each (the local map stays on disk as it
    // was and is "unavailable": no loop is verified against it, nothing folds into it).
    std::vector<std::string> take_paging_problems();

    // Paged-out local maps are read for it (not kept); an unavailable one is left out.
    common::PlyCloud global_map(map::GlobalMapStats* stats = nullptr) const;
    // Everything a saved map holds (local maps and keyframes shared, not copied); a paged-out
    // local map as its file (for a save into the directory it was paged from).
    map::MapData snapshot() const;
    // The same with every paged-out local map read back (not kept), for a save elsewhere; throws
    // common::IoError (one line) when one cannot be read.
    map::MapData complete_snapshot() const;
    std::size_t local_map_count() const { return maps_.size(); }
    // The sessions that built the map, the open ones last (each when it added anything), by id.
    std::vector<map::SessionRecord> sessions() const;
    std::size_t memory_bytes() const;
    // memory_bytes() by part: local maps (in memory; the paged-out ones' headers), keyframes
    // (their points and descriptors), graph (nodes, edges, odometry chains, the folds' records),
    // loop targets (the verification's cached grids), removed cells (what maintenance emptied).
    struct Memory {
        std::size_t local_maps = 0, keyframes = 0, graph = 0, loop_targets = 0, removed_cells = 0;
        std::size_t total() const {
            return local_maps + keyframes + graph + loop_targets + removed_cells;
        }
    };
    Memory memory() const;

  private:
    struct MapEntry {
        map::StoredLocalMap stored;
        std::uint64_t serial = 0;  // changes with every stored snapshot (verification cache key)
        // Paged out (stored.data == nullptr): the map's fields without its voxels, and whether
        // its file failed to load.
        std::shared_ptr<const common::LocalMapData> header{};
        bool unavailable = false;
    };
    // The local map's fields (its voxels only when in memory).
    static const common::LocalMapData& meta(const MapEntry& e) {
        return e.stored.data ? *e.stored.data : *e.header;
    }
    // Loads a paged-out local map back (kept); false when it is unavailable.
    bool page_in(std::uint64_t node, MapEntry& e);
    // Its content, read for the moment when paged out (nullptr: unavailable).
    std::shared_ptr<const common::LocalMapData> content(std::uint64_t node,
                                                        const MapEntry& e) const;
    using Folded = LongTermFolding::Folded;
    // What an open session holds of its own.
    struct Live {
        std::string robot;
        int cooldown = 0;
        map::SessionRecord record;                // stamps
        std::size_t keyframes_seen = 0;           // stored or not
        std::optional<Eigen::Vector3d> position;  // of the newest keyframe, world (paging)
    };
    int loops_between(std::uint64_t a, std::uint64_t b) const;  // active loop edges, either way
    using ChainAnchor = OdometryChains::Anchor;
    OdometryChains::View view() const { return {graph_, segments_, folding_}; }
    // Folds the finished local map of node `n` into an earlier map of the same place when the
    // conditions hold (mapper_long_term.cpp); the node it went into, or nullopt.
    std::optional<std::uint64_t> try_fold(std::uint64_t n);
    // n's anchor in into's anchor frame from registering n's surfaces to into's (from the graph's
    // estimate T_graph), when LongTermConfig::register_fold and the fit is accepted and within
    // fold_max_correction of T_graph; nothing otherwise (the fold then trusts the graph).
    std::optional<Eigen::Isometry3d> registered_fold(std::uint64_t n, std::uint64_t into,
                                                     const Eigen::Isometry3d& T_graph);
    void fold(std::uint64_t n, std::uint64_t into, const Eigen::Isometry3d& T_into_n);
    // The stored keyframe standing for a new keyframe at world pose T (long_term), if any.
    std::optional<std::uint32_t> stand_in(std::uint32_t session, std::uint64_t local_map_id,
                                          std::uint64_t node, const Eigen::Isometry3d& T_world,
                                          double stamp) const;
    bool tied_by_loop(std::uint64_t node) const;
    std::uint64_t ensure_node(std::uint32_t session, std::uint64_t local_map_id,
                              const Eigen::Isometry3d& T_odom_anchor,
                              std::optional<std::uint32_t> segment);
    void set_segment(std::uint32_t session, std::uint64_t local_map_id, std::uint32_t segment);
    // After an optimisation: segments that no loop joins to anything before them follow the map
    // before them.
    void place_unjoined_segments();
    // Appends the loop candidate by place (PlaceCandidateConfig) for a keyframe of `session` in
    // node `node` at T_anchor_lidar, with its descriptor, to the descriptor's candidates.
    void add_place_candidates(std::uint32_t session, std::uint64_t node,
                              const Eigen::Isometry3d& T_anchor_lidar,
                              const places::ScanContext& descriptor,
                              std::vector<LoopCandidate>* candidates) const;
    void verify(std::uint32_t session, const common::KeyframeData& keyframe,
                const std::vector<Eigen::Vector3f>& points, std::uint64_t node,
                const std::vector<LoopCandidate>& candidates, KeyframeResult* result);
    // A loop edge between two parts no loop had placed together (sessions): the part without a
    // fixed node, the later one, set rigidly where the edge puts it (the optimisation's start).
    void align_parts(const map::PoseGraphEdge& loop);
    // The odometry along which the graph's estimate between two nodes can have drifted, from
    // the nearest places already joined by loops (infinite across a segment break).
    double drift_path(std::uint64_t from, std::uint64_t to) const;
    // Why a measured relative pose between two placed nodes disagrees with the graph by more than
    // the loop consistency bounds allow after that drift; "" when it does not.
    std::string inconsistency(std::uint64_t from, std::uint64_t to, double disagreement,
                              double disagreement_deg) const;
    // A local map with the removed cells' voxels left out (nullptr: none of its voxels there).
    std::shared_ptr<const common::LocalMapData> without_removed(
        const common::LocalMapData& map, const Eigen::Isometry3d& T_world_anchor,
        std::size_t* removed) const;
    // Of the `flat` voxels of `map` (world frame by T) marked in `drop`, those that are ground
    // (MapEditConfig::ground_height) are unmarked.
    void keep_ground(const common::LocalMapData& map, const Eigen::Isometry3f& T,
                     const std::vector<std::size_t>& flat, std::vector<char>& drop) const;
    // True when the node's part is placed with the map's first session's (by loops or fixes).
    bool on_reference_part(std::uint64_t node) const;
    // The map's first session: the lowest with nodes (a loaded map's first, or the default).
    std::uint32_t reference_session() const;

    MapperConfig config_;
    std::uint32_t session_ = 0;
    std::uint64_t revision_ = 0;
    std::uint64_t next_node_ = 0;
    std::uint64_t next_serial_ = 1;
    PoseGraph graph_;
    LoopDetector detector_;
    registration::LoopVerifier verifier_;
    OdometryChains chains_;  // per session: local map id -> node, and the paths
    std::unordered_map<std::uint64_t, MapEntry> maps_;  // by node
    Segments segments_;  // of the nodes, and the parts loops placed together
    std::vector<std::shared_ptr<const map::StoredKeyframe>> keyframes_;
    std::vector<LoopClosure> loops_;
    std::map<std::uint32_t, Live> live_;  // the open sessions (the default one always)
    SessionJoins joins_;         // loops between open sessions' parts, held until enough agree
    std::size_t due_loops_ = 0;  // loops that made an optimisation due, since one
    LongTermFolding folding_;    // where the folded local maps went
    std::vector<map::SessionRecord> past_sessions_;  // of the loaded map
    std::unordered_map<std::uint64_t, int> fixes_per_node_;
    std::size_t map_fixes_ = 0;
    bool fixes_expected_ = false;
    RemovedCells removed_;  // what maintenance found gone
    std::size_t removed_voxels_ = 0;
    std::size_t forgotten_voxels_ = 0;
    FoldStats fold_stats_;
    std::deque<std::uint64_t> removal_waiting_;  // local maps to clear (remove_cells_in_steps)
    LocalMapLoader loader_;                      // paging: none, nothing is paged
    std::size_t paged_in_ = 0;
    mutable std::vector<std::string> paging_problems_;
};

}  // namespace ltm::mapping
