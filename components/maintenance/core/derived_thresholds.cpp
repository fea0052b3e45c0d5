#include "maintenance/core/derived_thresholds.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::maintenance {

namespace {

// Below this many slots of map time a voxel's histories cannot order its views: W1 rests on two
// or three slots, and the share of views that saw through a voxel tells more.
constexpr double kShortSessionSlots = 20.0;
constexpr double kShortFreeDominant = 0.6, kShortChangedScore = 0.2;

double finite_span(double span) { return std::isfinite(span) ? std::max(0.0, span) : 0.0; }

}  // namespace

double view_spacing_at(const MaintenanceConfig& config, double elapsed) {
    if (config.view_spacing) return *config.view_spacing;
    return std::min(kLongSession.view_spacing, finite_span(elapsed) / 50.0);
}

MaintenanceConfig resolve_thresholds(const MaintenanceConfig& config, const SessionSeen& seen) {
    MaintenanceConfig c = config;
    const double T = finite_span(seen.span);
    ChangeConfig& k = c.change;
    if (!c.view_spacing) c.view_spacing = view_spacing_at(config, T);
    if (!k.sigma) k.sigma = std::min(kLongSession.sigma, T / 10.0);
    if (!k.static_span) k.static_span = std::min(kLongSession.static_span, T / 4.0);
    if (!k.min_views)
        k.min_views =
            int(std::clamp<std::size_t>(seen.views / 3, 2, std::size_t(kLongSession.min_views)));
    const bool short_session = T < kShortSessionSlots * config.slot;
    if (!k.free_dominant)
        k.free_dominant = short_session ? kShortFreeDominant : kLongSession.free_dominant;
    if (!k.changed_score)
        k.changed_score = short_session ? kShortChangedScore : kLongSession.changed_score;
    return c;
}

}  // namespace ltm::maintenance
