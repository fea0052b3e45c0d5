#pragma once
// The thresholds of map maintenance that depend on time, from what the map has seen (issue 26,
// "safe maintenance defaults"). A threshold in seconds or in views only means something against
// how long, and how often, the map watched: `static_span: 3 s` on a one-second window calls no
// voxel static, so any changed voxel took its whole segment (a building, the street) along.
// Unset keys (maintenance_config.hpp) follow the current session's span of map time T (from its
// first scan to its latest) and its number of views N:
//   view_spacing  = min(0.2 s, T / 50)      at least ~50 views in any session, every scan of a
//                                           short window (decided scan by scan, T so far)
//   sigma         = min(1 s, T / 10)        the Eq. 14 kernel a tenth of what was watched
//   static_span   = min(3 s, T / 4)         hits over a quarter of the window prove the voxel
//                                           stays (hit spans are whole slots: T / 2 on a 1.6 s
//                                           window asked for three slots of 0.5 s)
//   min_views     = clamp(N / 3, 2, 4)      a third of the session's views, at most 4
//   free_dominant = 0.6 while T < 20 slots (10 s of 0.5 s), else 1 (off)
//   changed_score = 0.2 while T < 20 slots, else 0.35
//                   in a few seconds W1 rests on two or three slots (`slot`) and cannot order
//                   the views: the share of views that saw through a voxel tells more, and a
//                   one-sided history scores lower
// From T = 12 s (and N = 12 views) on every one of them is its long-session value (kLongSession),
// so sessions of minutes decide as before; a key given explicitly is kept as given.
#include <cstddef>

#include "maintenance/core/maintenance_config.hpp"

namespace ltm::maintenance {

// What the current session has shown the map.
struct SessionSeen {
    double span = 0.0;      // [s] of map time from the session's first scan to its latest
    std::size_t views = 0;  // views the session made
};

// The spacing of views `elapsed` seconds into a session (config.view_spacing when given).
double view_spacing_at(const MaintenanceConfig& config, double elapsed);

// `config` with every unset time-dependent key filled from `seen`; explicit keys kept.
MaintenanceConfig resolve_thresholds(const MaintenanceConfig& config, const SessionSeen& seen);

}  // namespace ltm::maintenance
