#pragma once
// The change decisions of map maintenance (METHOD.md section 5, Eq. 14).
//
// Per voxel: its hit times D_s against the times it was in view D_M (hit or seen through; only
// views that actually had it in range, in the field of view and not occluded count, so a region
// seen rarely is not called dynamic). The 1-D Wasserstein distance W1(D_s, D_M) is normalised by
// the largest it could be for that many hits among those views (all hits at the start, or all at
// the end): 0 for a voxel hit whenever in view, 1 for the most one-sided history. A voxel with a
// high score changed; its recent views tell how:
//   hit in (nearly) every recent view  -> new (seen in every recent view: it stays, and joins),
//   hit in few or none of them         -> gone: moving (all hits within a short span) or vanished.
// A voxel whose recent views all see through it is gone too, however long it was there before
// (a parked car that left, seen briefly from a later session).
// Per segment (ground removed, Euclidean clusters): when the share of its judged voxels that are
// gone reaches segment_fraction the segment is gone, and its voxels that could not be judged go
// with it (a moving car's last position, which no later view saw through); judged voxels keep
// their own verdict. A voxel whose hits span less than static_span has no verdict and follows its
// segment. A voxel whose latest view is older than the region's recent window (stale: the latest
// views never saw it, e.g. the roof of a car that left, with only sky behind it since) votes with
// its last verdict but goes with its segment when the segment vanished (mostly first seen in an
// earlier session); never with a passer-by of this session that touched it.
// A voxel flagged kMoving (an object the motion tracker saw move across scans put points in it:
// motion_tracker.hpp) that is not ground and was hit over at most motion.max_hit_span is moving,
// whatever its history, and leaves even an unchanged segment (a motorcyclist joined to the road).
#include <cstdint>
#include <functional>

#include "maintenance/core/change_set.hpp"
#include "maintenance/core/observation_map.hpp"

namespace ltm::maintenance {

enum class Verdict : std::uint8_t { kUnjudged, kStatic, kMoving, kVanished, kNew };

struct VoxelJudgement {
    Verdict verdict = Verdict::kUnjudged;
    double score = 0.0;  // normalised W1 [0, 1]
    std::uint32_t views = 0, hits = 0, recent_views = 0, recent_hits = 0;
    std::int32_t last_view_slot = 0;  // its latest view (hit or seen through)
};

// One voxel's verdict from its histories (slot width `slot` seconds).
VoxelJudgement judge_voxel(const ChangeConfig& config, double slot, const ObservedVoxel& voxel);

// One maintenance pass over a region: ground, segments, verdicts; the voxels that are gone are
// erased from the map and returned as changes (with new segments). A gone segment first seen
// before `session_start` (map time) vanished, else it moved. Segment ids start at *next_id, which
// is advanced. `between` (optional) runs between the pass's steps (ground, segments, verdicts,
// decisions): the caller's chance to spread a region's pass over time (issue 28: one region's
// pass in one piece was up to 0.2-0.5 s of a core); the result is the same as long as it does
// not touch the map.
ChangeSet maintain_region(const MaintenanceConfig& config, ObservationMap& map,
                          std::uint32_t session, double map_time, double session_start,
                          std::uint64_t* next_id, const std::function<void()>& between = {});

}  // namespace ltm::maintenance
