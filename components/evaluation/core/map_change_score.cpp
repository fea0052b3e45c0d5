#include "evaluation/core/map_change_score.hpp"

#include <algorithm>
#include <cmath>

#include "evaluation/core/point_grid.hpp"

namespace ltm::eval {
namespace {

// In o's grown box; a square around its footprint first (cheap).
bool inside(const Eigen::Vector3d& p, const SiteObject& o, double margin) {
    const double reach = 0.5 * std::hypot(o.length, o.width) + margin;
    if (std::abs(p.x() - o.x) > reach || std::abs(p.y() - o.y) > reach) return false;
    return o.contains(p, margin);
}

// Voxels of the object itself: inside its box and above the ground under it (where the object
// stands: a fence on a slope stands on higher ground than its base at one end).
std::size_t count_inside(const std::vector<Eigen::Vector3d>& map, const SiteObject& o,
                         const MapChangeConfig& config) {
    return static_cast<std::size_t>(
        std::count_if(map.begin(), map.end(), [&](const Eigen::Vector3d& p) {
            return inside(p, o, config.box_margin) &&
                   p.z() >= o.ground_at(p) + config.ground_clearance;
        }));
}

bool inside_any(const Eigen::Vector3d& p, const std::vector<SiteObject>& objects, double margin) {
    return std::any_of(objects.begin(), objects.end(),
                       [&](const SiteObject& o) { return inside(p, o, margin); });
}

}  // namespace

MapChangeScore score_map_changes(const std::vector<Eigen::Vector3d>& first_map,
                                 const std::vector<Eigen::Vector3d>& later_map,
                                 const ObjectChanges& changes,
                                 const std::vector<SiteObject>& unstable,
                                 const MapChangeConfig& config) {
    const double m = config.box_margin;
    MapChangeScore s;
    for (const auto& o : changes.removed) {
        s.removed_before += count_inside(first_map, o, config);
        s.removed_kept += count_inside(later_map, o, config);
    }
    for (const auto& o : changes.moved_from) {
        s.moved_from_before += count_inside(first_map, o, config);
        s.moved_from_kept += count_inside(later_map, o, config);
    }
    s.moved_objects = changes.moved_to.size();
    for (const auto& o : changes.moved_to) {
        const std::size_t n = count_inside(later_map, o, config);
        s.moved_to_voxels += n;
        if (n >= config.min_voxels) ++s.moved_to_present;
    }
    s.added_objects = changes.added.size();
    for (const auto& o : changes.added) {
        const std::size_t n = count_inside(later_map, o, config);
        s.added_voxels += n;
        if (n >= config.min_voxels) ++s.added_present;
    }
    std::vector<SiteObject> exclude = unstable;
    for (const auto* list :
         {&changes.removed, &changes.moved_from, &changes.moved_to, &changes.added})
        exclude.insert(exclude.end(), list->begin(), list->end());
    std::vector<Eigen::Vector3f> later;
    later.reserve(later_map.size());
    for (const auto& p : later_map) later.push_back(p.cast<float>());
    const PointGrid grid(later, config.static_radius);
    for (const auto& p : first_map) {
        if (inside_any(p, exclude, m)) continue;
        ++s.static_before;
        if (grid.has_neighbour(p.cast<float>()))
            ++s.static_kept;
        else
            s.static_lost.push_back(p);
    }
    return s;
}

}  // namespace ltm::eval
