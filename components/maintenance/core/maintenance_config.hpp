#pragma once
// Configuration of map maintenance (METHOD.md section 5): voxel resolution and time slots, what a
// view of the scene may judge (range image, margins), ground removal, segmentation, and the
// change decisions (Eq. 14 and the "beyond the paper" notes). Defaults suit a spinning LiDAR on a
// ground robot or car; every key is checked by validate().
//
// The keys whose right value depends on how long the map has watched (view_spacing,
// change.sigma, change.min_views, change.static_span, change.changed_score,
// change.free_dominant) are optional. Unset (the default), each follows what the map has seen:
// the span of map time T and the number of views N of the current session
// (derived_thresholds.hpp states every rule; each key's comment below gives its own); from 12 s
// of session on they are the long-session values (kLongSession), on a one-second window they
// shrink with it. A key given explicitly (YAML, --set, code) always wins, whatever the session.
#include <optional>
#include <string>

#include "common/core/config_check.hpp"

namespace ltm::maintenance {

// What the time-dependent keys are from 12 s of session on (and in a config used without
// resolve_thresholds()): the caps of the values derived from the data.
struct LongSessionValues {
    double view_spacing = 0.2;    // [s]
    double sigma = 1.0;           // [s]
    double changed_score = 0.35;  // normalised W1
    int min_views = 4;            // views
    double static_span = 3.0;     // [s]
    double free_dominant = 1.0;   // 1: off
};
inline constexpr LongSessionValues kLongSession{};

// The range image of a scan: what a view says about any small cube in its field of view.
struct RangeImageConfig {
    double azimuth_resolution = 0.2;    // [deg] pixel width
    double elevation_resolution = 0.2;  // [deg] pixel height (rows between beams stay empty)
    double min_range = 1.0;             // [m] nearer returns are ignored (the robot itself)
    double max_range = 120.0;           // [m] farther returns are ignored
    int max_samples = 5;                // pixels sampled per axis over a cube's angular footprint
    // Sky: a beam without a return that points at least sky_elevation above the horizon (the
    // world's, not the sensor's: the view's pose gives it) met nothing within the sensor's reach,
    // so a cube it passes through within sky_range is free, when no return around the cube
    // (within sky_clearance of it, across the beams) ends before the cube's far side: the edge
    // of an object standing next to the cube, or a dark or shiny spot on a surface that lost a
    // few returns, is not sky. Below the horizon a beam without a return says nothing (a dark
    // car's black paint). A fence segment taken down leaves sky where its upper half was: without
    // this its voxels above the sensor were never judged. sky_range 0 turns it off.
    double sky_elevation = 0.5;   // [deg] above the horizon (at 50 m: 0.44 m above the sensor)
    double sky_range = 50.0;      // [m] along a sky beam, free up to this range
    double sky_clearance = 0.25;  // [m] around a cube, no nearer return for sky to count
};

// Ground removal on the voxels: the lowest voxel of each column neighbourhood, and the voxels just
// above it whose normal is near vertical (no single plane: terrain slopes and roads tilt).
struct GroundConfig {
    double column_size = 1.0;  // [m] 2-D cells
    int neighbourhood = 2;     // cells each way searched for the local lowest voxel
    double height = 0.3;       // [m] above the local lowest: ground (with a near-vertical normal)
    double max_tilt = 35.0;    // [deg] between a ground voxel's normal and the vertical
    double flatness = 0.05;    // [m] z spread of a ground voxel's points when they have no plane
};

// Euclidean clustering of the remaining voxels into segments (PCL).
struct SegmentationConfig {
    double tolerance = 0.55;  // [m] between voxel centres of one segment
    int min_voxels = 1;
};

// The decisions (Eq. 14): per voxel, the normalised W1 between its hit times and its view times;
// per segment, the share of its judged voxels that changed. std::optional: unset follows the data
// (see the top of this file; a config never resolved acts as a long session).
struct ChangeConfig {
    std::optional<double> sigma;   // [s] of map time: the kernel of Eq. 14 (unset: min(1, T/10))
    std::optional<int> min_views;  // views (hit or seen through) before a voxel is judged
                                   // (unset: N/3 in [2, 4])
    // normalised W1 (0 = always seen, 1 = the most one-sided); unset: 0.2 while T < 20 slots,
    // else 0.35
    std::optional<double> changed_score;
    double min_free_fraction = 0.2;  // a voxel seen through in fewer of its views is unchanged
    double recent_window = 20.0;     // [s] of map time before a voxel's last view: "recent"
    int min_recent_views = 3;        // recent views needed to call a voxel vanished or new
    double new_hit_fraction = 0.8;   // hit in at least this share of recent views: new (kept)
    double gone_hit_fraction = 0.1;  // hit in at most this share of recent views: gone
    double moving_span = 15.0;  // [s] all hits within this span and gone: moving, else vanished
    // [s] hits spanning less than this prove nothing: such a voxel (say, the last position of a
    // car that no later view saw through) follows its segment's verdict (unset: min(3, T/4)).
    std::optional<double> static_span;
    double segment_fraction = 0.5;  // share of a segment's judged voxels that changed: it did
    // A voxel seen through in at least this share of its views changed, whatever its W1 (an
    // actor that walks back and forth along one path is there now and then, never for long);
    // 1 turns this off (unset: 0.6 while T < 20 slots, else 1).
    std::optional<double> free_dominant;
    // Changed voxels of unchanged segments are removed too when their score reaches this (a
    // fence segment taken down, still joined to the rest of the fence; site_sessions: its points
    // removed 0.2 % -> 80 %, static kept 99.95 -> 99.94 %); 1 turns this off.
    double voxel_score = 0.9;
    bool voxel_level = false;  // also remove changed voxels of unchanged segments
    // A gone voxel that an earlier session hit and this session never hit, seen through in at
    // least this many recent views (none of them a hit), is removed even from an unchanged
    // segment, whatever its score: a fence segment taken down, joined to the fence left standing,
    // whose earlier sessions' grazing views saw through its thin cubes now and then (W1 0.6-0.75,
    // under voxel_score; site_week day 4 kept 195 of 210 voxels of fence 6). A static surface in
    // the cube returns at it to some beam of a session that sees it that often. 0 turns it off.
    int through_views = 10;
    // [m] A voxel under one this pass removes (gone, there before this session), in the same
    // column and down to this far below it, goes with it when this session neither hit nor
    // viewed it and an earlier one made it: an object's lowest part, which the session's rays
    // near the ground never reached past what stands in between (site_week day 2: the lower
    // side of a car that left, 28 m from the route, kept under its removed upper side). Ground
    // voxels and voxels this session saw stay (a static voxel seen today keeps its own verdict).
    // 0 turns it off.
    double reach_down = 1.5;
};

// Motion of objects across the scans of a short window (motion_tracker.hpp states the rule):
// per scan, the non-ground points in clusters, linked scan to scan; a cluster displaced from its
// linked ancestor min_lag..max_lag s earlier by at least min_shift as a rigid shape, into and out
// of places that were not occupied (one of them seen empty), is moving: its voxels leave the map
// (unless ground, or hit over more than max_hit_span: a parked car stays whatever a pair said).
struct MotionConfig {
    bool enabled = true;
    // [s] followed only this far into a session: from about 12 s on, a voxel's views order its
    // history (derived_thresholds.hpp) and what moves is seen through; the tracker costs tens of
    // ms a scan, which a robot's whole-day session must not pay (issue 28's budget)
    double session_span = 12.0;
    double cell = 0.2;             // [m] cells of a scan's points
    int neighbourhood = 1;         // cells each way that join a cluster (twice that vertically)
    double join_distance = 0.3;    // [m] ... when their points' means are this close horizontally
    double ground_column = 1.0;    // [m] columns for the scan's ground
    double ground_height = 0.3;    // [m] cells this close to the local lowest are ground
    int min_cells = 6;             // smaller clusters are not followed
    int max_cells = 3000;          // larger ones neither (buildings, rows of trees)
    double max_extent = 8.0;       // [m] horizontal: larger clusters are not objects
    double max_height = 4.0;       // [m] vertical extent of an object
    double min_lag = 0.4;          // [s] scans compared are this far apart ...
    double max_lag = 1.0;          // [s] ... and at most this
    double max_speed = 25.0;       // [m/s] the search radius for the same object earlier
    double min_shift = 0.3;        // [m] smaller displacements are registration noise
    double match_distance = 0.25;  // [m] a cell matches a cell of the other scan this close
    double min_match = 0.6;        // share of cells matched both ways at the displacement
    double max_overlap = 0.2;      // share of the known cells occupied at the other scan's time
    double min_known = 0.5;        // share of cells the other scan saw (occupied or through)
    double max_hit_span = 2.0;     // [s] a voxel hit over a longer span is kept
};

struct MaintenanceConfig {
    double voxel_size = 0.25;   // [m] maintenance voxels (finer than the registration voxels)
    double region_size = 40.0;  // [m] the map is maintained in square regions of this size
    double slot = 0.5;          // [s] of map time: the histogram slot of a voxel's times
    int max_slots = 6;          // entries a voxel keeps of its view history (older ones merge);
                                // at most VoxelHistory::kCapacity (6: the compact voxel state)
    double max_range = 50.0;    // [m] a view judges voxels within this range
    // [m] In a region an earlier session mapped, a point farther than this from the sensor that
    // lands in an empty cell next to a voxel of an earlier session creates no voxel (it adds to
    // voxels that exist; a cell with no such neighbour, a new object, is created); nearer points,
    // and every point of a region first seen in this session, create voxels (0: every point
    // creates). Repeated ground: another day's sparse far rings land between and beside the
    // cells the earlier days filled, so the map would grow every day with no new ground (issue
    // 26 item 4; components/maintenance/README.md, "Repeated ground").
    double create_range = 0.0;
    double free_margin = 0.3;  // [m] a return this much beyond a cube (plus half its diagonal)
    double free_margin_per_m = 0.01;  // [m/m] ... plus this per metre of range: seen through
    // [m] a return behind a cube counts as at it (a hit) only within this (plus half its
    // diagonal, plus hit_margin_per_m per metre of range) of the cube's centre along the beam; one
    // farther, but not beyond the free margin, is another surface just behind the cube and says
    // nothing (a van's side 0.7 m in front of the next van's kept "hits" from it, seen from 33-50
    // m, after the van left). The per-metre term is smaller than free_margin_per_m: an angular
    // pose error moves a return across the beam, hardly along it. hit_margin = free_margin and
    // hit_margin_per_m = free_margin_per_m: the rule before (every return within the free
    // margin is a hit).
    double hit_margin = 0.1;
    double hit_margin_per_m = 0.002;  // [m/m]
    // [s] scans become views at most this often (unset: min(0.2, T/50), T so far)
    std::optional<double> view_spacing;
    double view_delay = 10.0;   // [s] a view judges the voxels that exist this long after it
    double session_gap = 60.0;  // [s] of map time between the end of a session and the next
    RangeImageConfig range_image;
    GroundConfig ground;
    SegmentationConfig segmentation;
    ChangeConfig change;
    MotionConfig motion;
};

template <class Visitor>
void visit_fields(MaintenanceConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "voxel_size", c.voxel_size, in_range(0.02, 5.0));
    v(prefix + "region_size", c.region_size, above(1.0));
    v(prefix + "slot", c.slot, positive);
    v(prefix + "max_slots", c.max_slots, in_range(2, 6));  // VoxelHistory::kCapacity
    v(prefix + "max_range", c.max_range, positive);
    v(prefix + "create_range", c.create_range, non_negative);
    v(prefix + "free_margin", c.free_margin, non_negative);
    v(prefix + "free_margin_per_m", c.free_margin_per_m, non_negative);
    v(prefix + "hit_margin", c.hit_margin, non_negative);
    v(prefix + "hit_margin_per_m", c.hit_margin_per_m, non_negative);
    v(prefix + "view_spacing", c.view_spacing, non_negative);
    v(prefix + "view_delay", c.view_delay, non_negative);
    v(prefix + "session_gap", c.session_gap, non_negative);
    v(prefix + "range_image.azimuth_resolution", c.range_image.azimuth_resolution,
      in_range(0.01, 10.0));
    v(prefix + "range_image.elevation_resolution", c.range_image.elevation_resolution,
      in_range(0.01, 10.0));
    v(prefix + "range_image.min_range", c.range_image.min_range, non_negative);
    v(prefix + "range_image.max_range", c.range_image.max_range, positive);
    v(prefix + "range_image.max_samples", c.range_image.max_samples, in_range(1, 64));
    v(prefix + "range_image.sky_elevation", c.range_image.sky_elevation, in_range(0.0, 90.0));
    v(prefix + "range_image.sky_range", c.range_image.sky_range, non_negative);
    v(prefix + "range_image.sky_clearance", c.range_image.sky_clearance, in_range(0.0, 10.0));
    v(prefix + "ground.column_size", c.ground.column_size, positive);
    v(prefix + "ground.neighbourhood", c.ground.neighbourhood, in_range(0, 20));
    v(prefix + "ground.height", c.ground.height, non_negative);
    v(prefix + "ground.max_tilt", c.ground.max_tilt, in_range(0.0, 90.0));
    v(prefix + "ground.flatness", c.ground.flatness, non_negative);
    v(prefix + "segmentation.tolerance", c.segmentation.tolerance, positive);
    v(prefix + "segmentation.min_voxels", c.segmentation.min_voxels, at_least(1));
    v(prefix + "change.sigma", c.change.sigma, non_negative);
    v(prefix + "change.min_views", c.change.min_views, at_least(1));
    v(prefix + "change.changed_score", c.change.changed_score, unit);
    v(prefix + "change.min_free_fraction", c.change.min_free_fraction, unit);
    v(prefix + "change.recent_window", c.change.recent_window, non_negative);
    v(prefix + "change.min_recent_views", c.change.min_recent_views, at_least(1));
    v(prefix + "change.new_hit_fraction", c.change.new_hit_fraction, unit);
    v(prefix + "change.gone_hit_fraction", c.change.gone_hit_fraction, unit);
    v(prefix + "change.moving_span", c.change.moving_span, non_negative);
    v(prefix + "change.static_span", c.change.static_span, non_negative);
    v(prefix + "change.segment_fraction", c.change.segment_fraction, unit);
    v(prefix + "change.free_dominant", c.change.free_dominant, unit);
    v(prefix + "change.voxel_score", c.change.voxel_score, unit);
    v(prefix + "change.voxel_level", c.change.voxel_level, unchecked);
    v(prefix + "change.through_views", c.change.through_views, non_negative);
    v(prefix + "change.reach_down", c.change.reach_down, non_negative);
    v(prefix + "motion.enabled", c.motion.enabled, unchecked);
    v(prefix + "motion.session_span", c.motion.session_span, non_negative);
    v(prefix + "motion.cell", c.motion.cell, in_range(0.02, 2.0));
    v(prefix + "motion.neighbourhood", c.motion.neighbourhood, in_range(1, 5));
    v(prefix + "motion.join_distance", c.motion.join_distance, positive);
    v(prefix + "motion.ground_column", c.motion.ground_column, positive);
    v(prefix + "motion.ground_height", c.motion.ground_height, non_negative);
    v(prefix + "motion.min_cells", c.motion.min_cells, at_least(1));
    v(prefix + "motion.max_cells", c.motion.max_cells, at_least(1));
    v(prefix + "motion.max_extent", c.motion.max_extent, positive);
    v(prefix + "motion.max_height", c.motion.max_height, positive);
    v(prefix + "motion.min_lag", c.motion.min_lag, positive);
    v(prefix + "motion.max_lag", c.motion.max_lag, in_range(0.01, 10.0));
    v(prefix + "motion.max_speed", c.motion.max_speed, positive);
    v(prefix + "motion.min_shift", c.motion.min_shift, positive);
    v(prefix + "motion.match_distance", c.motion.match_distance, positive);
    v(prefix + "motion.min_match", c.motion.min_match, unit);
    v(prefix + "motion.max_overlap", c.motion.max_overlap, unit);
    v(prefix + "motion.min_known", c.motion.min_known, unit);
    v(prefix + "motion.max_hit_span", c.motion.max_hit_span, non_negative);
}

// A visitor of visit_fields that passes the optional keys on only when they are given (checking
// a config: an unset key has no value to check).
template <class Visitor>
struct GivenFields {
    Visitor& visitor;
    template <class T, class Rule>
    void operator()(const std::string& key, T& field, const Rule& rule) {
        visitor(key, field, rule);
    }
    template <class T, class Rule>
    void operator()(const std::string& key, std::optional<T>& field, const Rule& rule) {
        if (field) visitor(key, *field, rule);
    }
};

// The first problem of a configuration (key relative to it), rules across fields included.
std::optional<common::ConfigProblem> validate(const MaintenanceConfig& config);

}  // namespace ltm::maintenance
