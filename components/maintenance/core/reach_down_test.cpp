// change.reach_down: a van that left, joined to the wall behind it (one segment, unchanged), seen
// on its last day only above a low wall that stands between the route and its place: the upper
// side is seen through and leaves, the lower side, which no ray of the day reached, goes with it.
#include "maintenance/core/reach_down.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "maintenance/core/long_term_map.hpp"
#include "maintenance/core/test_scene.hpp"

namespace ltm::maintenance {
namespace {

using test::Box;
using Cells = std::set<std::tuple<int, int, int>>;

MaintenanceConfig scene_config() {
    MaintenanceConfig c;
    c.view_spacing = 0.0;
    c.view_delay = 5.0;
    c.session_gap = 10.0;
    return c;
}

// A straight drive along y = `y` from x = x0 to x1 at `speed` m/s, 5 scans a second; the cells
// of box `track_id`'s points into `made`.
void drive(LongTermMap& map, const std::vector<Box>& boxes, double x0, double x1, double y,
           double speed, double* stamp, Cells* made = nullptr, int track_id = -100) {
    const int n = std::max(1, int(std::abs(x1 - x0) / speed * 5.0));
    const float s = float(map.config().voxel_size);
    for (int k = 0; k <= n; ++k) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(x0 + (x1 - x0) * double(k) / n, y, 1.0);
        std::vector<int> ids;
        const std::vector<Eigen::Vector3f> pts = test::cast(boxes, T, &ids);
        map.add_scan(pts, T, *stamp);
        for (std::size_t i = 0; made && i < pts.size(); ++i) {
            if (ids[i] != track_id) continue;
            const Eigen::Vector3f w = T.cast<float>() * pts[i];
            made->insert({int(std::floor(w.x() / s)), int(std::floor(w.y() / s)),
                          int(std::floor(w.z() / s))});
        }
        *stamp += 0.2;
    }
}

std::size_t kept_of(const LongTermMap& map, const Cells& cells) {
    std::size_t n = 0;
    const float s = float(map.config().voxel_size);
    for (const auto& [x, y, z] : cells)
        n += map.keeps(Eigen::Vector3f((x + 0.5f) * s, (y + 0.5f) * s, (z + 0.5f) * s)) ? 1 : 0;
    return n;
}

struct VanDay {
    std::size_t low = 0, low_kept = 0, high = 0, high_kept = 0, wall = 0, wall_kept = 0;
};

// Two days with the van parked 0.4 m in front of a wall, a third without it, seen from behind a
// 1 m wall 4 m from the route.
VanDay van_left(const MaintenanceConfig& config) {
    const Box wall{{-12, 10.2f, 0}, {12, 10.4f, 2.5f}, 1};
    const Box van{{-2, 8, 0}, {2, 9.8f, 1.8f}, 2};
    const Box low_wall{{-8, 4, 0}, {8, 4.2f, 1.0f}, 3};
    LongTermMap map(config);
    Cells van_cells, wall_cells;
    double stamp = 0.0;
    for (std::uint32_t day = 0; day < 2; ++day) {
        map.begin_session(day, stamp);
        drive(map, {wall, van}, -8, 8, 0, 2.0, &stamp, &van_cells, 2);
        drive(map, {wall, van}, 8, -8, 0, 2.0, &stamp, &wall_cells, 1);
        map.end_session();
        stamp += 86400.0;
    }
    map.begin_session(2, stamp);
    drive(map, {wall, low_wall}, -8, 8, 0, 4.0, &stamp);
    drive(map, {wall, low_wall}, 8, -8, 0, 4.0, &stamp);
    map.end_session();
    VanDay out;
    for (const auto& c : van_cells) {
        const int z = std::get<2>(c);
        if (z < 1) continue;  // the ground's row
        const std::size_t kept = kept_of(map, {c});
        if (z < 4) {  // under 1 m: behind the low wall on the last day
            ++out.low;
            out.low_kept += kept;
        } else {
            ++out.high;
            out.high_kept += kept;
        }
    }
    for (const auto& c : wall_cells) {
        if (std::get<2>(c) < 1) continue;
        ++out.wall;
        out.wall_kept += kept_of(map, {c});
    }
    return out;
}

TEST(ReachDown, LowSideOfAVanThatLeftGoesWithItsUpperSide) {
    const VanDay day = van_left(scene_config());
    ASSERT_GT(day.low, 20u);
    ASSERT_GT(day.high, 20u);
    ASSERT_GT(day.wall, 200u);
    EXPECT_LE(day.high_kept, day.high / 2) << day.high_kept << " of " << day.high;
    EXPECT_LE(day.low_kept, day.low / 3) << day.low_kept << " of " << day.low;
    EXPECT_GE(day.wall_kept, day.wall * 99 / 100) << day.wall_kept << " of " << day.wall;
    // Without it the lower side stays: no ray of the last day reached it, and its segment (the
    // van joined to the wall) is unchanged.
    MaintenanceConfig off = scene_config();
    off.change.reach_down = 0.0;
    const VanDay before = van_left(off);
    EXPECT_GE(before.low_kept, before.low * 9 / 10) << before.low_kept << " of " << before.low;
    std::printf(
        "van's lower side kept: %zu of %zu (without reach_down: %zu); upper %zu of %zu; "
        "wall %zu of %zu\n",
        day.low_kept, day.low, before.low_kept, day.high_kept, day.high, day.wall_kept, day.wall);
}

}  // namespace
}  // namespace ltm::maintenance
