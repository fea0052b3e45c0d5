#pragma once
// Folding one local map into another of the same place (issue 13, "a map that grows with the
// site"): the voxels of `add` moved into the grid frame of `into` and merged voxel by voxel on its
// lattice, so that a revisit updates the existing local map instead of adding a new one.
//   a voxel of `add` lands in the cell floor(p_grid / voxel_size) of `into`'s lattice; where the
//   cell is taken, the two voxels become one:
//     centre      point-count weighted mean (stays in the cell: both centres are in it)
//     normal      sign-aligned (the added one turned to the existing one's side) point-count
//                 weighted mean, normalised; the better-supported voxel's normal when the mean
//                 cancels out, the other's when one has none
//     point_count, life.observations: summed (saturating)
//     planarity, stability: point-count weighted means; life.health: observation-weighted mean
//     life.created = min, life.last_seen = max, life.seen: the union of both, as indices into the
//     merged observation_times
//   observation_times: the sorted union of both maps' stamps, bounded (bound_observation_times).
// A surface seen again lands partly in cells next to the ones it filled before (a few cm of
// another day's pose, another viewpoint): with same_surface > 0, a voxel of `add` whose cell is
// empty in `into` but lies on the surface patch of a voxel of `into` in a neighbouring cell (its
// centre within same_surface x voxel_size of that voxel's plane, normals within 30 deg, the
// centre's foot on the plane inside that voxel's cell widened by a tenth of an edge) is merged
// into that voxel (centre: its foot, clamped into the cell) instead of adding a voxel; a surface
// that extends beyond the patch (its foot outside the cell) still adds voxels. So a place driven
// again grows with what is new there, not with the days (issue 26, repeated ground).
// With beside_surface > 0, a voxel of `add` in a cell empty in `into` (and not taken so) that lies
// next to a voxel of `into` (26 neighbouring cells) with a normal, its centre within
// beside_surface x voxel_size of that voxel's plane and its normal (if any) within 30 deg of it,
// adds nothing but the old voxel's last sighting (life.last_seen, life.seen): the old surface one
// cell beyond the old patch, as another day's slightly different view shows it (on repeat_week
// 85-90 % of the voxels a revisit added were beside an old voxel). An empty cell between voxels of
// `into` (both cells of an opposite pair of its neighbours hold one: a hole maintenance emptied or
// earlier days' returns missed) is not an edge and is filled as before. A really new surface loses
// only its cells that touch the old one on its plane: a new object standing on old ground (its
// faces off the ground's plane) enters whole, new ground beyond the old keeps all but its first
// ring. The result keeps `into`'s id, segment, anchor, grid, voxel size and finished flag; its
// revision is `into`'s + 1 and its box covers both.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/core/local_map_data.hpp"

namespace ltm::mapping {

// The stamps kept when a map's observation times grow beyond `max_times` (>= 2): the newest
// max_times / 2 stamps are all kept; the older ones are thinned evenly to the remaining
// max_times - max_times / 2 (the oldest and the last of them always among them, the rest at equal
// steps of their index), so that old sessions keep a sparser but even record and the recent
// history stays whole. Returns, for each input stamp, the index of the kept stamp that stands for
// it (a dropped stamp: the kept one nearest in time), and the kept stamps in *kept. Input sorted
// ascending; nothing is dropped when it has at most max_times stamps.
std::vector<std::uint32_t> bound_observation_times(const std::vector<double>& times,
                                                   std::size_t max_times,
                                                   std::vector<double>* kept);

// `into` with the voxels of `add` folded in (see above). T_into_add: `add`'s anchor in `into`'s
// anchor frame. max_observation_times: see bound_observation_times (at most 65536: life.seen
// holds 16-bit indices). same_surface: see above (0: off). *absorbed_count (if given): the voxels
// of `add` merged so into a neighbouring cell's voxel. beside_surface: see above (0: off);
// *beside_count (if given): the voxels of `add` left out so.
common::LocalMapData merge_local_maps(const common::LocalMapData& into,
                                      const common::LocalMapData& add,
                                      const Eigen::Isometry3d& T_into_add,
                                      std::size_t max_observation_times, double same_surface = 0.0,
                                      std::size_t* absorbed_count = nullptr,
                                      double beside_surface = 0.0,
                                      std::size_t* beside_count = nullptr);

// Voxel life on repeated ground (METHOD.md section 5: a voxel's life from its last observation and
// the map's time; issue 26, "bounded"). A local map's visits are its observation times split where
// more than visit_gap seconds pass between two stamps (the robot left the place and came back: a
// later lap, another day). A voxel last seen before the after_visits-th last visit began has been
// missed by the map's last after_visits visits: whatever made it (another day's noise at a
// cell's edge, a passing object maintenance did not catch, a surface since gone out of view) is no
// longer seen there, and it leaves the map. Without this a place driven every day thickens by a
// few per cent a day (repeat_fortnight, components/bench/lifelong/README.md). after_visits <= 0:
// nothing is forgotten. Observation times sorted ascending (as merge_local_maps leaves them).
// Returns the voxels removed.
std::size_t forget_unseen_voxels(common::LocalMapData* map, int after_visits, double visit_gap);

}  // namespace ltm::mapping
