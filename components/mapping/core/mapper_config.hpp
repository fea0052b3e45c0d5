#pragma once
// Configuration of the mapping back end (METHOD.md section 3): one plain struct with defaults for
// a Velodyne HDL-64E on a car (KITTI), and the information of odometry and loop edges.
#include <optional>
#include <string>

#include "common/core/config_check.hpp"
#include "common/core/sensor_preset.hpp"
#include "map/core/global_map.hpp"
#include "mapping/core/loop_detector.hpp"
#include "mapping/core/pose_graph.hpp"
#include "places/core/scan_context.hpp"
#include "registration/core/loop_verifier.hpp"

namespace ltm::mapping {

// Standard deviations of an odometry edge between consecutive anchors d metres apart:
// sigma = floor + per_metre * d (translation per axis, rotation per axis).
struct OdometryEdgeConfig {
    double sigma_translation = 0.05;        // [m]
    double sigma_translation_per_m = 0.01;  // [m/m]
    double sigma_rotation = 0.05;           // [deg]
    double sigma_rotation_per_m = 0.005;    // [deg/m]
};

// Standard deviations of a verified loop edge.
struct LoopEdgeConfig {
    double sigma_translation = 0.1;  // [m]
    double sigma_rotation = 0.3;     // [deg]
};

// A verified loop whose relative anchor pose disagrees with the graph's current estimate by more
// than floor + per_m * (odometry between the two anchors, from the nearest places that loops
// already join) is refused (same session only): the estimate cannot have drifted that much, so
// the registration found another place.
struct LoopConsistencyConfig {
    double translation = 2.0;         // [m]
    double translation_per_m = 0.03;  // [m/m]
    double rotation = 5.0;            // [deg]
    double rotation_per_m = 0.05;     // [deg/m]
};

// A map that grows with the site, not with the distance driven (issue 13, "sessions on one map"):
// a finished local map of the current session at a place already mapped by an earlier lap or
// session is folded into the existing local map there (local_map_merge.hpp) instead of becoming a
// new graph node, and keyframes at mapped places are not stored again.
struct LongTermConfig {
    bool merge = true;  // fold local maps of mapped places into the existing ones
    // A finished local map whose anchor (world pose, from the graph) is within this distance of
    // an earlier lap's or session's anchor is folded into the nearest such map, when a verified
    // loop ties it to the map (never on odometry alone). Default: half the odometry's local-map
    // switch distance (20 m, odometry_config.hpp): anchors along a road driven again are at most
    // half a switch distance from the nearest earlier one.
    double merge_distance = 10.0;  // [m]
    // A keyframe whose world pose is within this distance and angle of a stored keyframe of an
    // earlier lap or session is not stored (its loops are still searched and verified, named by
    // the stored keyframe that stands for it); only where the graph's pose is tied by a loop.
    // A 360 deg sensor's keyframe stands for every heading (its descriptors are searched over
    // all column shifts, its points verify a loop from either way): mapper_preset() sets 180 for
    // spinning sensors, so a road driven both ways keeps one set of keyframes.
    double keyframe_distance = 1.0;  // [m]
    double keyframe_angle = 15.0;    // [deg] (180: any heading)
    // A verified loop between places already joined by loops that agrees with the graph's
    // estimate to within these is added as an edge without making an optimisation due.
    double agree_translation = 0.1;  // [m]
    double agree_rotation = 1.0;     // [deg]
    // A merged local map's observation times are bounded (local_map_merge.hpp: the newest half
    // kept, the older ones thinned evenly); at most 65536 (16-bit indices in the life records).
    int max_observation_times = 1024;
    // A folded map's voxel landing in a cell next to an existing voxel, on that voxel's surface
    // patch (within this fraction of the voxel size of its plane, local_map_merge.hpp), is merged
    // into it instead of adding a voxel: a place driven again does not grow by the few cm another
    // day's pose and view move its surfaces across cell faces. 0: off.
    double same_surface = 0.2;  // [voxel sizes]
    // A folded map's voxel landing in an empty cell next to an existing voxel, within this
    // fraction of the voxel size of that voxel's plane (normals within 30 deg), adds nothing: the
    // old surface one cell beyond its patch, as another day's view shows it (local_map_merge.hpp;
    // a new object's faces off the old planes still enter). 0: off (robot_lifelong.yaml: 0.5).
    double beside_surface = 0.0;  // [voxel sizes]
    // Voxel life (local_map_merge.hpp, forget_unseen_voxels): a folded local map's voxel that its
    // last forget_after_visits visits (stretches of its observation times more than visit_gap
    // apart: another day, or a round an hour later) did not see leaves it, so a place driven every
    // day stays the size of what is there, not of every day's noise at its edges (issue 26,
    // "bounded"). The laps of one long day are one visit: with a 60 s gap each lap was one, and
    // eight laps in 13 minutes forgot 45 k voxels (12 %) of a yard's map, static ones that only
    // some views see among them. 0: voxels are never forgotten (only maintenance removes).
    int forget_after_visits = 3;
    double visit_gap = 3600.0;  // [s]
    // A local map folded into an earlier session's map (another day's) is folded where
    // registering its surfaces to that map's (the loop verification's registration, from the
    // graph's estimate) puts it, when that fit is accepted and within fold_max_correction /
    // _rotation of the graph's estimate; otherwise (or when false), and always between maps of
    // open sessions (one day's laps: the graph's estimate is the loops' consensus, and the
    // registration overrode it, site_loop day 0 0.065 -> 0.087 m), where the graph puts it. The
    // graph places a day's maps by that day's localisation and loops, a cm or two off the old
    // surfaces: folded so, each day moved the map's voxels by a share of that offset while its
    // keyframes stayed (repeat_fortnight: the same scans localised 3.9 cm apart on day 1's and day
    // 8's maps; components/bench/lifelong/README.md).
    bool register_fold = true;
    double fold_max_correction = 0.5;           // [m]
    double fold_max_correction_rotation = 2.0;  // [deg]
};

// Joining two robots' sessions (open in one Mapper at once) that no loop has placed together yet.
// Such a loop is judged by the verification alone (no odometry bounds where one session lies in
// the other), and a site of repeated bays and fences can fool it once: the first loop is held until
// `loops` loops in all, from at least two keyframes and between local maps whose odometry segment
// is known, agree on where the one part lies in the other (each predicts the other's relative pose
// to within agree_translation / agree_rotation); then all of them join the parts.
struct SessionJoinConfig {
    int loops = 2;                   // agreeing loops that join two parts (1: the first one joins)
    double agree_translation = 2.0;  // [m]
    double agree_rotation = 3.0;     // [deg]
};

// Loop candidates by place between robots (open sessions) that loops have placed together: the
// graph says where the other robot's keyframes lie, so a keyframe within `radius` of one (world
// positions) is verified against that keyframe's local map from the graph's estimate, also when
// their descriptors do not match (the robots cross or turn at the same spot with other headings,
// or pass a few metres apart: a Scan Context is made for a revisit along the same path). The
// nearest such keyframe whose local map is not among the descriptor's candidates and not yet
// joined to the keyframe's by max_loops_per_anchor_pair loops, one a keyframe, after the
// descriptor's candidates. Default: the verification's reach from a matched keyframe's place
// (verification.max_correction_translation): a revisit farther than that is not one the
// verifier accepts from a descriptor either. 0: off. Within one session, and towards an earlier
// session's (loaded) map, loops are found by descriptor only.
struct PlaceCandidateConfig {
    double radius = 8.0;  // [m]
};

// Ties from localisation (Mapper::add_map_fix): a session continuing a loaded map is placed on it
// by the localisation's pose of its keyframes (registered to that map's voxels), not only by loops.
// A fix is an edge from the nearest loaded keyframe's node to the keyframe's local map node, with
// the loop edge's information; the first one places the session's part (or an odometry segment
// after a break) where it says, later ones must agree with the graph within the loop consistency
// bounds (drift since the places already joined). A local map is rigid: a few fixes a map suffice.
struct MapFixConfig {
    bool enabled = true;
    int per_local_map = 2;  // fixes kept a local map
    // The nearest loaded keyframe within this distance of the fix gives the edge's other end.
    double radius = 30.0;  // [m]
};

// The keyframes' localisation descriptor (ScanContext++, kind kMeanVariance), saved in the map
// for global localisation; its range and sensor height follow scan_context's in mapper_preset().
inline places::ScanContextConfig default_localisation_descriptor() {
    places::ScanContextConfig c;
    c.kind = places::ScanContextKind::kMeanVariance;
    c.rings = 20;
    c.sectors = 60;
    return c;
}

// A loaded map's edge (issue 26). A loop from this session's keyframe to a local map of a loaded
// (earlier) session is refused when that local map explains fewer than `overlap` of the
// keyframe's points in any direction (azimuth sector, verification.sectors, holding at least
// verification.min_sector_share of them): a keyframe at the map's edge, where the map ahead is
// only what an earlier day saw from afar. Such a registration is pulled along the road towards
// the map (the same ~0.1 m the localisation's edge_overlap keeps out of tracking); tied, it puts
// the new road that far off in the saved map. Loops deeper in the map tie it instead. 0: off,
// the default: on site_week it refused the loops of 26-101 keyframes a day and changed no day's
// rmse (the rejoin's loops passed it; mapping/README.md), so it is a switch to try, not a default.
struct MapEdgeConfig {
    double overlap = 0.0;  // inlier fraction in the keyframe's worst-explained direction
};

// Paging the local maps (issue 28 item 3, mapper_paging.cpp): when the Mapper is given a loader
// (the mapping component does with a site directory), a local map that a save wrote and that has
// not changed since leaves memory once it lies farther than `radius` from the newest keyframe of
// every open session (by its anchor); it is loaded back when a loop's
// verification, a fold, a maintenance edit, the global map or a save elsewhere needs it.
// 0: never. 150 m: beyond a loop candidate's search and a revisit's fold on any of our data.
struct PagingConfig {
    double radius = 150.0;  // [m]
};

// Map maintenance's edits (remove_cells, issue 26). A voxel goes when a removed cell lies near its
// centre (half its edge); besides, a cell of a vanished object (a vanished segment of at least
// `surface_min_cells` maintenance cells: an object that stood there on an earlier day) takes the
// voxels whose own surface it lies on (within `surface_band` of the voxel's plane) within one voxel
// edge of their centre, when that surface is not the ground's (its normal at least
// `surface_min_tilt` from the vertical: maintenance never removes ground, and an object's foot lies
// on the ground's plane beside it). Why: maintenance makes no voxel of its own for a return beyond
// its create_range on ground an earlier day mapped (the return adds to a voxel beside it), so the
// side of a parked car seen only from afar, which the local maps hold as voxels of their own,
// has no removed cell near their centres when the car leaves: on repeat_fortnight 2-11 such
// voxels a day stayed, the lowest 0.6 m of cars' sides above the ground (their centres 0.4-0.6 m
// from the car's removed cells). surface_band 0: off.
// Ground stays: a voxel whose plane is near horizontal (its normal within surface_min_tilt of the
// vertical) and whose centre lies within `ground_height` of the lowest voxel centre of its local
// map within `ground_reach` (horizontally, on a lattice of 1 m columns) is ground, and no removed
// cell takes it. Maintenance never removes ground voxels, but the cells it removes reach down to
// the ground: a pedestrian's or a car's lowest cell holds the ground's points under its feet or
// wheels, and a far patch of ground maintenance did not recognise as ground is judged vanished
// when another day's grazing rays pass through it. On long_day (8 laps over day 0's map), 630 of
// day 0's 926 static voxels lost after day 1 were such ground (components/mapping/README.md,
// "Ground stays"). An object's roof or a container's top stands higher than its reach above the
// ground around it and still goes. ground_height 0: off.
struct MapEditConfig {
    double surface_band = 0.15;      // [m]
    int surface_min_cells = 10;      // a vanished segment's cells
    double surface_min_tilt = 35.0;  // [deg] between the voxel's normal and the vertical
    double ground_height = 0.3;      // [m] above the lowest voxel around: ground (0: off)
    double ground_reach = 2.0;       // [m] around a voxel, where its lowest is looked for
};

struct MapperConfig {
    places::ScanContextConfig scan_context;  // loop closure
    places::ScanContextConfig localisation_descriptor = default_localisation_descriptor();
    LoopDetectorConfig loop_detection;
    registration::LoopVerifierConfig verification;
    PoseGraphConfig pose_graph;
    OdometryEdgeConfig odometry_edge;
    LoopEdgeConfig loop_edge;
    LoopConsistencyConfig loop_consistency;
    map::GlobalMapConfig global_map;
    LongTermConfig long_term;
    SessionJoinConfig session_join;
    PlaceCandidateConfig place_candidates;
    MapFixConfig map_fix;
    MapEdgeConfig map_edge;
    PagingConfig paging;
    MapEditConfig map_edits;
    int max_loops_per_keyframe = 1;  // verified loops kept a keyframe (best candidates first)
    // After a keyframe closes a loop, this many following keyframes are not verified (their
    // descriptors are still kept): a revisit is closed every few keyframes, not at each one.
    int loop_cooldown_keyframes = 2;
    // Within a session, the verification starts first from the graph's estimate of the keyframe
    // in the candidate's anchor (the odometry with the loops so far, usually well within the
    // registration's basin), then from the descriptor's guess (the matched keyframe's place
    // turned by the descriptor's yaw, metres away on a revisit that does not retrace the path).
    bool verify_from_graph = true;
    // Loop edges kept between the same two local maps (0: no limit). Local maps are rigid, so each
    // loop measures the same relative pose again; later candidates between them are not verified.
    // Two rather than one: against an odometry edge that is off (a drift jump), a single loop
    // edge pulls too weakly (KITTI forward/reverse test: 0.14 m with one, 0.06 m with two or more).
    int max_loops_per_anchor_pair = 2;
    bool keep_keyframe_points = false;  // keep each keyframe's scan in the map (memory, files)
    // Detect and verify loops. Off (a map from a known trajectory: the poses are final), keyframes
    // only get their descriptors and are kept (searchable by a later session's loop closure).
    bool loop_closure = true;
};

// The defaults for a sensor preset: its row of common/core/sensor_preset.hpp gives the descriptor
// range and sensor height (as mounted), the loop search and the verification (`narrow`: a shorter
// range, a nearer and stricter search, fewer inliers); the rest the defaults.
MapperConfig mapper_preset(common::SensorPreset preset);

// Calls v(key, field, rule) for the mapper's own fields (edges, loop consistency, loop policy), by
// the dotted key as in YAML; the rule is the field's (common/core/config_check.hpp).
template <class Visitor>
void visit_own_fields(MapperConfig& c, Visitor&& v) {
    using namespace common::rules;
    auto& o = c.odometry_edge;
    v("odometry_edge.sigma_translation", o.sigma_translation, positive);
    v("odometry_edge.sigma_translation_per_m", o.sigma_translation_per_m, non_negative);
    v("odometry_edge.sigma_rotation", o.sigma_rotation, positive);
    v("odometry_edge.sigma_rotation_per_m", o.sigma_rotation_per_m, non_negative);
    v("loop_edge.sigma_translation", c.loop_edge.sigma_translation, positive);
    v("loop_edge.sigma_rotation", c.loop_edge.sigma_rotation, positive);
    auto& k = c.loop_consistency;
    v("loop_consistency.translation", k.translation, positive);
    v("loop_consistency.translation_per_m", k.translation_per_m, non_negative);
    v("loop_consistency.rotation", k.rotation, positive);
    v("loop_consistency.rotation_per_m", k.rotation_per_m, non_negative);
    v("max_loops_per_keyframe", c.max_loops_per_keyframe, at_least(1));
    v("loop_cooldown_keyframes", c.loop_cooldown_keyframes, non_negative);
    v("paging.radius", c.paging.radius, non_negative);
    v("map_edits.surface_band", c.map_edits.surface_band, non_negative);
    v("map_edits.surface_min_cells", c.map_edits.surface_min_cells, at_least(1));
    v("map_edits.surface_min_tilt", c.map_edits.surface_min_tilt, in_range(0.0, 90.0));
    v("map_edits.ground_height", c.map_edits.ground_height, non_negative);
    v("map_edits.ground_reach", c.map_edits.ground_reach, in_range(0.0, 20.0));
    v("verify_from_graph", c.verify_from_graph, unchecked);
    v("max_loops_per_anchor_pair", c.max_loops_per_anchor_pair, non_negative);
    v("keep_keyframe_points", c.keep_keyframe_points, unchecked);
    v("loop_closure", c.loop_closure, unchecked);
    auto& l = c.long_term;
    v("long_term.merge", l.merge, unchecked);
    v("long_term.merge_distance", l.merge_distance, positive);
    v("long_term.keyframe_distance", l.keyframe_distance, non_negative);
    v("long_term.keyframe_angle", l.keyframe_angle, non_negative);
    v("long_term.agree_translation", l.agree_translation, non_negative);
    v("long_term.agree_rotation", l.agree_rotation, non_negative);
    v("long_term.max_observation_times", l.max_observation_times, in_range(2, 65536));
    v("long_term.same_surface", l.same_surface, in_range(0.0, 0.5));
    v("long_term.beside_surface", l.beside_surface, in_range(0.0, 1.0));
    v("long_term.forget_after_visits", l.forget_after_visits, non_negative);
    v("long_term.visit_gap", l.visit_gap, positive);
    v("long_term.register_fold", l.register_fold, unchecked);
    v("long_term.fold_max_correction", l.fold_max_correction, positive);
    v("long_term.fold_max_correction_rotation", l.fold_max_correction_rotation, positive);
    auto& j = c.session_join;
    v("session_join.loops", j.loops, at_least(1));
    v("session_join.agree_translation", j.agree_translation, positive);
    v("session_join.agree_rotation", j.agree_rotation, positive);
    v("place_candidates.radius", c.place_candidates.radius, non_negative);
    v("map_fix.enabled", c.map_fix.enabled, unchecked);
    v("map_fix.per_local_map", c.map_fix.per_local_map, at_least(1));
    v("map_fix.radius", c.map_fix.radius, positive);
    v("map_edge.overlap", c.map_edge.overlap, unit);
}

// Every field but the Scan Context kinds (enums: loaders read scan_context.kind as a name; the
// localisation descriptor is always ScanContext++): the parts', then the mapper's own.
template <class Visitor>
void visit_fields(MapperConfig& c, Visitor&& v) {
    visit_fields(c.scan_context, "scan_context.", v);
    visit_fields(c.localisation_descriptor, "localisation_descriptor.", v);
    visit_fields(c.loop_detection, "loop_detection.", v);
    visit_fields(c.verification, "verification.", v);
    visit_fields(c.pose_graph, "pose_graph.", v);
    visit_fields(c.global_map, "global_map.", v);
    visit_own_fields(c, v);
}

// The first problem, the key as in YAML ("scan_context.rings"); nullopt when valid. The Mapper
// throws common::ConfigError under "mapping".
std::optional<common::ConfigProblem> validate(const MapperConfig& config);

// 6x6 information matrices of e = [dt; dr] (pose_graph.hpp).
Matrix6d odometry_information(const OdometryEdgeConfig& config, double distance);
Matrix6d loop_information(const LoopEdgeConfig& config);

// The edge into the first local map of a new odometry segment (common::LocalMapData::segment: the
// odometry lost track and restarted at its best estimate, the prediction). Its measurement is
// that estimate, which is not an odometry measurement: sigma 100 m per axis and 180 deg per axis,
// about 1e6 times less information than a loop edge (0.1 m / 0.3 deg) in translation and 4e5 in
// rotation. Why an edge at all: the graph stays one connected part, the gauge stays the session's
// first anchor, and the segment keeps its place relative to the map before it until a loop joins
// it (the Mapper sets that place exactly after each optimisation: the solver barely moves along
// so weak an edge). Why this weak: a loop that joins the segment must place it on its own; against
// a 5 m / 40 deg break the edge pulls the loop edge and the odometry chains by well under a
// millimetre (mapper_segment_test: the joined anchors end within 3 mm of the truth). Fixed, not
// configurable, so that a saved graph shows its breaks (is_segment_break) without a change of the
// map format.
Matrix6d segment_break_information();
// An odometry edge with exactly segment_break_information().
bool is_segment_break(const map::PoseGraphEdge& edge);

}  // namespace ltm::mapping
