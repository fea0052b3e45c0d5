#include "evaluation/core/object_account.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace ltm::eval {
namespace {

bool in_box(const Eigen::Vector3d& p, const SiteObject& o, double margin) {
    const double reach = 0.5 * std::hypot(o.length, o.width) + margin;
    if (std::abs(p.x() - o.x) > reach || std::abs(p.y() - o.y) > reach) return false;
    return o.contains(p, margin);
}

struct PlaceCounter {
    const SiteObject& place;
    std::vector<const SiteObject*> standing;  // today's objects near the place
    const MapChangeConfig& config;

    // The place's voxels of `map`; their heights above the base in `heights` when given.
    std::size_t count(const std::vector<Eigen::Vector3d>& map,
                      std::vector<double>* heights = nullptr) const {
        std::size_t n = 0;
        for (const auto& p : map) {
            if (!in_box(p, place, config.box_margin) ||
                p.z() < place.ground_at(p) + config.ground_clearance)
                continue;
            const bool other = std::any_of(standing.begin(), standing.end(), [&](const auto* s) {
                return in_box(p, *s, config.box_margin);
            });
            if (other) continue;
            ++n;
            if (heights) heights->push_back(p.z() - place.base_z);
        }
        return n;
    }
};

}  // namespace

std::vector<ObjectAccount> account_left_places(
    const std::vector<Eigen::Vector3d>& first_map, const std::vector<Eigen::Vector3d>& start_map,
    const std::vector<Eigen::Vector3d>& later_map, const ObjectChanges& changes,
    const std::vector<SiteObject>& yesterday_objects, const std::vector<SiteObject>& today_objects,
    const std::vector<Eigen::Vector3d>& route, const MapChangeConfig& config) {
    std::unordered_map<std::uint32_t, const SiteObject*> yesterday;
    for (const auto& o : yesterday_objects) yesterday[o.id] = &o;
    std::vector<ObjectAccount> out;
    auto account = [&](const SiteObject& o, const char* what) {
        ObjectAccount a;
        a.object = o;
        a.what = what;
        const auto it = yesterday.find(o.id);
        // Today's change when it stood at its first place the day before.
        a.today =
            it != yesterday.end() && std::hypot(it->second->x - o.x, it->second->y - o.y) <= 0.1;
        a.route_distance = std::numeric_limits<double>::infinity();
        for (const auto& p : route)
            a.route_distance = std::min(a.route_distance, std::hypot(p.x() - o.x, p.y() - o.y));
        const double reach = 0.5 * std::hypot(o.length, o.width) + config.box_margin;
        PlaceCounter counter{o, {}, config};
        for (const auto& s : today_objects) {
            const double near = reach + 0.5 * std::hypot(s.length, s.width) + config.box_margin;
            if (std::hypot(s.x - o.x, s.y - o.y) <= near) counter.standing.push_back(&s);
        }
        a.before = counter.count(first_map);
        a.at_start = counter.count(start_map);
        std::vector<double> heights;
        a.kept = counter.count(later_map, &heights);
        if (!heights.empty()) {
            const auto mid = heights.begin() + static_cast<long>(heights.size() / 2);
            std::nth_element(heights.begin(), mid, heights.end());
            a.kept_median_height = *mid;
        }
        out.push_back(a);
    };
    for (const auto& o : changes.removed) account(o, "removed");
    for (const auto& o : changes.moved_from) account(o, "moved");
    return out;
}

AccountTotals sum_accounts(const std::vector<ObjectAccount>& accounts, const std::string& what,
                           bool today) {
    AccountTotals t;
    for (const auto& a : accounts) {
        if (a.what != what || a.today != today) continue;
        ++t.objects;
        t.before += a.before;
        t.kept += a.kept;
    }
    return t;
}

}  // namespace ltm::eval
