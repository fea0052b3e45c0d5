#pragma once
// Object by object, what the maps of a lifelong run keep of the places changed objects left
// (removed objects, moved objects' first places): the voxels of the place in the first day's map,
// in the map the session started from and in the map after it, whether the object left today
// (it stood there the day before) or on an earlier day, and how near the day's route came.
// The simulator plans each day's changes against the first day, so an object removed on day 1 can
// stand again on day 2 and be removed again on day 3: "today" tells what one session had to see.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "evaluation/core/map_change_score.hpp"
#include "evaluation/core/site_objects.hpp"

namespace ltm::eval {

struct ObjectAccount {
    SiteObject object;   // at its first day's place
    std::string what;    // "removed" or "moved"
    bool today = false;  // it stood at its first place the day before (left in this session)
    double route_distance = 0.0;  // [m] nearest scan position of the day to its footprint centre
    // Its voxels: in the first map, in the map the session started from, in the map after it.
    std::size_t before = 0, at_start = 0, kept = 0;
    double kept_median_height = 0.0;  // [m] above its base, of the voxels kept (0: none)
};

// Voxels of a place: in the object's box grown by `config.box_margin`, at least
// `config.ground_clearance` above the ground under it (SiteObject::ground_at), and in no grown box
// of an object that stands on the day (`today_objects`: a neighbour parked within the margin is no
// voxel of the place). `yesterday_objects` tells which objects left today; `route` is the day's
// true path.
std::vector<ObjectAccount> account_left_places(
    const std::vector<Eigen::Vector3d>& first_map, const std::vector<Eigen::Vector3d>& start_map,
    const std::vector<Eigen::Vector3d>& later_map, const ObjectChanges& changes,
    const std::vector<SiteObject>& yesterday_objects, const std::vector<SiteObject>& today_objects,
    const std::vector<Eigen::Vector3d>& route, const MapChangeConfig& config = {});

// Sums over the accounts of one kind ("removed" / "moved"), today's or earlier ones.
struct AccountTotals {
    std::size_t objects = 0, before = 0, kept = 0;
};
AccountTotals sum_accounts(const std::vector<ObjectAccount>& accounts, const std::string& what,
                           bool today);

}  // namespace ltm::eval
