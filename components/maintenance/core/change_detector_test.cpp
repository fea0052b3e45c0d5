// Change detection on small ray-cast scenes with exact ground truth: boxes on a flat ground seen by
// a 32-beam LiDAR, across one or two sessions.
#include "maintenance/core/change_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "common/core/config_check.hpp"
#include "maintenance/core/long_term_map.hpp"
#include "maintenance/core/test_scene.hpp"

namespace ltm::maintenance {
namespace {

using test::Box;
using test::cast;

Eigen::Isometry3d at(double x, double y) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, 1.0);
    return T;
}

MaintenanceConfig test_config() {
    MaintenanceConfig c;
    c.view_spacing = 0.0;
    c.view_delay = 5.0;
    c.session_gap = 10.0;
    return c;
}

// Drives a straight line from a to b at `speed` m/s, 5 scans a second.
void drive(LongTermMap& map, const std::vector<Box>& boxes, Eigen::Vector2d a, Eigen::Vector2d b,
           double speed, double* stamp, std::set<std::tuple<int, int, int>>* made = nullptr,
           int track_id = -100) {
    const double length = (b - a).norm();
    const int n = std::max(1, int(length / speed * 5.0));
    for (int k = 0; k <= n; ++k) {
        const Eigen::Vector2d p = a + (b - a) * (double(k) / n);
        const Eigen::Isometry3d T = at(p.x(), p.y());
        std::vector<int> ids;
        const std::vector<Eigen::Vector3f> pts = cast(boxes, T, &ids);
        map.add_scan(pts, T, *stamp);
        if (made) {
            for (std::size_t i = 0; i < pts.size(); ++i) {
                if (ids[i] != track_id) continue;
                const Eigen::Vector3f w = T.cast<float>() * pts[i];
                const float s = float(map.config().voxel_size);
                made->insert({int(std::floor(w.x() / s)), int(std::floor(w.y() / s)),
                              int(std::floor(w.z() / s))});
            }
        }
        *stamp += 0.2;
    }
}

// How many of the cells the map still keeps.
std::size_t kept_of(const LongTermMap& map, const std::set<std::tuple<int, int, int>>& cells) {
    std::size_t n = 0;
    const float s = float(map.config().voxel_size);
    for (const auto& [x, y, z] : cells)
        n += map.keeps(Eigen::Vector3f((x + 0.5f) * s, (y + 0.5f) * s, (z + 0.5f) * s)) ? 1 : 0;
    return n;
}

TEST(ChangeDetector, ParkedCarThatLeftIsRemovedWallKeptNewContainerAdded) {
    const Box wall{{-15, 8, 0}, {15, 8.3f, 3}, 1};
    const Box car{{0, -5, 0}, {4, -3.2f, 1.5f}, 2};
    const Box container{{-9, -5.5f, 0}, {-6, -3, 2.5f}, 3};
    LongTermMap map(test_config());
    std::set<std::tuple<int, int, int>> car_cells, wall_cells, container_cells;
    double stamp = 1000.0;
    map.begin_session(0, stamp);
    drive(map, {wall, car}, {-12, 0}, {12, 0}, 2.0, &stamp, &car_cells, 2);
    drive(map, {wall, car}, {12, 0}, {12, 0.1}, 2.0, &stamp, &wall_cells, 1);
    const ChangeSet first = map.end_session();
    EXPECT_LE(first.voxels_removed, first.voxels_before / 100) << "a static session";
    ASSERT_GT(car_cells.size(), 50u);
    EXPECT_EQ(kept_of(map, car_cells), car_cells.size()) << "the car was parked all session";

    stamp = 1000.0 + 3 * 86400.0;  // three days later
    map.begin_session(1, stamp);
    drive(map, {wall, container}, {12, 0}, {-12, 0}, 2.0, &stamp, &container_cells, 3);
    drive(map, {wall, container}, {-12, 12}, {12, 12}, 2.0, &stamp, &wall_cells, 1);
    const ChangeSet second = map.end_session();

    // The car's foot (the lowest 0.25 m) shares its voxels with the ground it stood on: they stay.
    std::set<std::tuple<int, int, int>> car_body;
    for (const auto& c : car_cells)
        if (std::get<2>(c) >= 1) car_body.insert(c);
    car_cells = car_body;
    const std::size_t car_kept = kept_of(map, car_cells);
    EXPECT_LE(car_kept, car_cells.size() / 20) << car_kept << " of " << car_cells.size();
    EXPECT_GE(second.count(ChangeReason::kVanished), 1u);
    ASSERT_GT(wall_cells.size(), 100u);
    EXPECT_GE(kept_of(map, wall_cells), wall_cells.size() * 99 / 100) << "both faces of the wall";
    ASSERT_GT(container_cells.size(), 50u);
    EXPECT_GE(kept_of(map, container_cells), container_cells.size() * 95 / 100);
    EXPECT_GE(second.count(ChangeReason::kNew), 1u);
}

TEST(ChangeDetector, MovingCarRemovedWithinOneSession) {
    const Box wall{{-30, 9, 0}, {30, 9.3f, 3}, 1};
    LongTermMap map(test_config());
    std::set<std::tuple<int, int, int>> trace, wall_cells;
    double stamp = 0.0;
    map.begin_session(0, stamp);
    // The robot creeps along y = 0 while a car drives past at 5 m/s along y = -6.
    for (int k = 0; k <= 50; ++k) {
        const double x_car = -20.0 + 5.0 * 0.2 * k;
        const Box car{{float(x_car), -6.9f, 0.3f}, {float(x_car + 4), -5.1f, 1.5f}, 2};
        const Eigen::Isometry3d T = at(-2.0 + 0.08 * k, 0.0);
        std::vector<int> ids;
        const std::vector<Eigen::Vector3f> pts = cast({wall, car}, T, &ids);
        map.add_scan(pts, T, stamp);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const Eigen::Vector3f w = T.cast<float>() * pts[i];
            const float s = float(map.config().voxel_size);
            const std::tuple<int, int, int> cell{
                int(std::floor(w.x() / s)), int(std::floor(w.y() / s)), int(std::floor(w.z() / s))};
            if (ids[i] == 2) trace.insert(cell);
            if (ids[i] == 1) wall_cells.insert(cell);
        }
        stamp += 0.2;
    }
    const ChangeSet c = map.end_session();
    ASSERT_GT(trace.size(), 100u);
    const std::size_t left = kept_of(map, trace);
    EXPECT_LE(left, trace.size() / 20) << left << " of " << trace.size() << " trace voxels left";
    EXPECT_GE(c.count(ChangeReason::kMoving), 1u);
    EXPECT_GE(kept_of(map, wall_cells), wall_cells.size() * 99 / 100);
}

// A pass spread over time (LongTermMap::maintain with work between its regions, as the component
// paces it) decides exactly as the pass in one go: the same changes, the same map.
TEST(ChangeDetector, SpreadPassesKeepTheSameMap) {
    const Box wall{{-30, 9, 0}, {30, 9.3f, 3}, 1};
    const Box shed{{-25, -12, 0}, {-20, -9, 2.5f}, 4};
    MaintenanceConfig config = test_config();
    config.region_size = 10.0;  // several regions in view at once
    LongTermMap burst(config), spread(config);
    std::vector<ChangeSet> burst_passes, spread_passes;
    std::size_t betweens = 0, scan_betweens = 0;
    double stamp = 0.0;
    burst.begin_session(0, stamp);
    spread.begin_session(0, stamp);
    for (int k = 0; k <= 60; ++k) {
        const double x_car = -20.0 + 5.0 * 0.2 * k;
        const Box car{{float(x_car), -6.9f, 0.3f}, {float(x_car + 4), -5.1f, 1.5f}, 2};
        const Eigen::Isometry3d T = at(-6.0 + 0.2 * k, 0.0);
        const std::vector<Eigen::Vector3f> pts = cast({wall, shed, car}, T);
        burst.add_scan(pts, T, stamp);
        spread.add_scan(pts, T, stamp, [&] { ++scan_betweens; });
        stamp += 0.2;
        if (k % 15 == 14) {  // a pass every 3 s
            burst_passes.push_back(burst.maintain());
            spread_passes.push_back(spread.maintain([&] { ++betweens; }));
        }
    }
    burst_passes.push_back(burst.end_session());
    spread_passes.push_back(spread.end_session());
    // Between the regions and between each region's steps (ground, segments, verdicts).
    EXPECT_GE(betweens, 3u * (spread_passes.size() - 1)) << "passes over several regions";
    // And between the regions each scan's view judged (issue 28: a scan's work spread too).
    EXPECT_GE(scan_betweens, 60u) << "views over several regions";
    ASSERT_EQ(burst_passes.size(), spread_passes.size());
    std::size_t removed = 0;
    for (std::size_t i = 0; i < burst_passes.size(); ++i) {
        const ChangeSet &a = burst_passes[i], &b = spread_passes[i];
        EXPECT_EQ(a.voxels_removed, b.voxels_removed) << i;
        EXPECT_EQ(a.voxels_before, b.voxels_before) << i;
        ASSERT_EQ(a.changes.size(), b.changes.size()) << i;
        for (std::size_t j = 0; j < a.changes.size(); ++j) {
            EXPECT_EQ(a.changes[j].id, b.changes[j].id);
            EXPECT_EQ(a.changes[j].reason, b.changes[j].reason);
            EXPECT_EQ(a.changes[j].voxels.size(), b.changes[j].voxels.size());
        }
        removed += a.voxels_removed;
    }
    EXPECT_GT(removed, 100u) << "the passing car left the map";
    std::vector<Eigen::Vector3f> ca = burst.voxel_centres(), cb = spread.voxel_centres();
    ASSERT_EQ(ca.size(), cb.size());
    for (std::size_t i = 0; i < ca.size(); ++i) ASSERT_EQ(ca[i], cb[i]) << i;
    EXPECT_EQ(burst.stats().voxels, spread.stats().voxels);
}

// One second of a 10 Hz LiDAR standing at the origin: a wall, a post, and a motorcyclist (1 m
// long) riding 2 m along y = -5 past the post (0.3 m from its path: one segment with it); the
// map with `config`. Returns how many of the rider's voxels and of the static ones it keeps.
struct ShortWindow {
    std::size_t rider = 0, rider_kept = 0, stat = 0, stat_kept = 0;
};
ShortWindow one_second_window(const MaintenanceConfig& config) {
    const Box wall{{-20, -9.3f, 0}, {20, -9, 3}, 1};
    const Box post{{2.6f, -4.6f, 0}, {2.9f, -4.3f, 2.0f}, 3};
    LongTermMap map(config);
    std::set<std::tuple<int, int, int>> rider, stat;
    const float s = float(map.config().voxel_size);
    const auto cell = [&](const Eigen::Vector3f& w) {
        return std::tuple<int, int, int>{int(std::floor(w.x() / s)), int(std::floor(w.y() / s)),
                                         int(std::floor(w.z() / s))};
    };
    map.begin_session(0, 100.0);
    for (int k = 0; k <= 10; ++k) {
        const float x = 1.0f + 0.2f * float(k);
        const Box bike{{x, -5.5f, 0.3f}, {x + 1.0f, -4.9f, 1.6f}, 2};
        const Eigen::Isometry3d T = at(0.0, 0.0);
        std::vector<int> ids;
        const std::vector<Eigen::Vector3f> pts = cast({wall, post, bike}, T, &ids);
        map.add_scan(pts, T, 100.0 + 0.1 * k);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const Eigen::Vector3f w = T.cast<float>() * pts[i];
            if (ids[i] == 2) rider.insert(cell(w));
            if ((ids[i] == 1 || ids[i] == 3) && w.z() > s) stat.insert(cell(w));
        }
    }
    map.end_session();
    ShortWindow out;
    for (const auto& c : rider) out.rider += stat.count(c) ? 0 : 1;  // the rider's own voxels
    for (const auto& c : rider)
        if (!stat.count(c)) out.rider_kept += kept_of(map, {c});
    out.stat = stat.size();
    out.stat_kept = kept_of(map, stat);
    return out;
}

TEST(ChangeDetector, OneSecondWindowKeepsTheStaticSceneAndRemovesTheMover) {
    // The defaults: the thresholds follow the window's span (1 s) and views (11).
    const ShortWindow w = one_second_window(MaintenanceConfig{});
    ASSERT_GT(w.rider, 40u);
    ASSERT_GT(w.stat, 500u);
    EXPECT_GE(w.stat_kept, w.stat * 99 / 100) << w.stat_kept << " of " << w.stat;
    EXPECT_LE(w.rider_kept, w.rider / 10) << w.rider_kept << " of " << w.rider << " left";

    // The long-session values given explicitly still win, and show why they are not the
    // defaults any more: no voxel of a second is static, so the post goes with the rider.
    MaintenanceConfig fixed;
    fixed.view_spacing = kLongSession.view_spacing;
    fixed.change.sigma = kLongSession.sigma;
    fixed.change.min_views = kLongSession.min_views;
    fixed.change.static_span = kLongSession.static_span;
    fixed.change.free_dominant = kLongSession.free_dominant;
    fixed.change.changed_score = kLongSession.changed_score;
    const ShortWindow old = one_second_window(fixed);
    EXPECT_LT(old.stat_kept, old.stat * 99 / 100) << old.stat_kept << " of " << old.stat;
}

// A fence of three segments in a row (one segment of the map: they touch), 0.1 m thick in 0.25 m
// cubes, mapped over two sessions from two roads at 1 m/s; on the third the middle one is gone
// and the robot drives past both ways at 4 m/s (few views against the earlier sessions' many).
// How many of the middle one's voxels (above the ground's, 0.5 m from the joints) and of the
// standing ones' the map with `config` keeps.
struct FenceDay {
    std::size_t gone = 0, gone_kept = 0, standing = 0, standing_kept = 0;
};
FenceDay fence_taken_down(const MaintenanceConfig& config) {
    const Box left{{-10, 8, 0}, {-4, 8.1f, 2.4f}, 1};
    const Box middle{{-4, 8, 0}, {4, 8.1f, 2.4f}, 2};
    const Box right{{4, 8, 0}, {10, 8.1f, 2.4f}, 3};
    LongTermMap map(config);
    std::set<std::tuple<int, int, int>> middle_cells, standing_cells;
    double stamp = 0.0;
    map.begin_session(0, stamp);
    drive(map, {left, middle, right}, {-12, 0}, {12, 0}, 1.0, &stamp, &middle_cells, 2);
    map.end_session();
    stamp += 86400.0;
    map.begin_session(1, stamp);
    drive(map, {left, middle, right}, {12, 3}, {-12, 3}, 1.0, &stamp, &middle_cells, 2);
    map.end_session();
    stamp += 86400.0;
    map.begin_session(2, stamp);
    drive(map, {left, right}, {-12, 0}, {12, 0}, 4.0, &stamp, &standing_cells, 1);
    drive(map, {left, right}, {12, 0}, {-12, 0}, 4.0, &stamp, &standing_cells, 3);
    map.end_session();
    FenceDay out;
    const auto above_ground = [](const std::set<std::tuple<int, int, int>>& cells) {
        std::set<std::tuple<int, int, int>> out;
        for (const auto& c : cells)
            if (std::get<2>(c) >= 1) out.insert(c);
        return out;
    };
    middle_cells = above_ground(middle_cells);
    standing_cells = above_ground(standing_cells);
    // Away from the joints (0.5 m each side: the standing segments' end faces)
    for (auto it = middle_cells.begin(); it != middle_cells.end();) {
        const float x = (float(std::get<0>(*it)) + 0.5f) * float(map.config().voxel_size);
        it = std::abs(x) > 3.5f ? middle_cells.erase(it) : std::next(it);
    }
    out.gone = middle_cells.size();
    out.gone_kept = kept_of(map, middle_cells);
    out.standing = standing_cells.size();
    out.standing_kept = kept_of(map, standing_cells);
    return out;
}

TEST(ChangeDetector, FenceSegmentTakenDownLeavesTheFenceLeftStanding) {
    const FenceDay day = fence_taken_down(test_config());
    ASSERT_GT(day.gone, 200u);
    ASSERT_GT(day.standing, 400u);
    EXPECT_LE(day.gone_kept, day.gone / 8) << day.gone_kept << " of " << day.gone << " kept";
    EXPECT_GE(day.standing_kept, day.standing * 99 / 100)
        << day.standing_kept << " of " << day.standing;
    // Without change.through_views much of it stays: seen through in under a fifth of their views
    // (score 0) or, where the earlier sessions' views saw through the thin cubes now and then,
    // scoring under voxel_score, in the fence's unchanged segment.
    MaintenanceConfig off = test_config();
    off.change.through_views = 0;
    const FenceDay before = fence_taken_down(off);
    EXPECT_GT(before.gone_kept, before.gone / 4) << before.gone_kept << " of " << before.gone;
    std::printf(
        "taken-down segment kept: %zu of %zu voxels (without the rule: %zu); standing: %zu of "
        "%zu\n",
        day.gone_kept, day.gone, before.gone_kept, day.standing_kept, day.standing);
}

TEST(ChangeDetector, RegionSeenRarelyIsNotCalledDynamic) {
    // A shed in range only at the start and the end of the session: its views are all hits.
    const Box shed{{-37, 3, 0}, {-33, 7, 2.5f}, 4};
    LongTermMap map(test_config());
    std::set<std::tuple<int, int, int>> cells;
    double stamp = 0.0;
    map.begin_session(0, stamp);
    drive(map, {shed}, {0, 0}, {40, 0}, 4.0, &stamp, &cells, 4);
    drive(map, {shed}, {40, 0}, {0, 0}, 4.0, &stamp, &cells, 4);
    const ChangeSet c = map.end_session();
    ASSERT_GT(cells.size(), 20u);
    EXPECT_EQ(kept_of(map, cells), cells.size());
    EXPECT_EQ(c.voxels_removed, 0u);
}

TEST(ChangeDetector, VoxelVerdicts) {
    ChangeConfig config;
    ObservedVoxel v;
    EXPECT_EQ(judge_voxel(config, 0.5, v).verdict, Verdict::kUnjudged);
    for (int s = 0; s < 40; ++s) v.history.add(s, true, VoxelHistory::kCapacity);
    EXPECT_EQ(judge_voxel(config, 0.5, v).verdict, Verdict::kStatic);
    ObservedVoxel gone;  // hit for 20 s, then seen through for 20 s
    for (int s = 0; s < 40; ++s) gone.history.add(s, true, VoxelHistory::kCapacity);
    for (int s = 40; s < 80; ++s) gone.history.add(s, false, VoxelHistory::kCapacity);
    const VoxelJudgement g = judge_voxel(config, 0.5, gone);
    EXPECT_EQ(g.verdict, Verdict::kVanished);
    EXPECT_NEAR(g.score, 1.0, 0.05);
    ObservedVoxel fresh;  // seen through for 20 s, then hit
    for (int s = 0; s < 40; ++s) fresh.history.add(s, false, VoxelHistory::kCapacity);
    for (int s = 40; s < 80; ++s) fresh.history.add(s, true, VoxelHistory::kCapacity);
    EXPECT_EQ(judge_voxel(config, 0.5, fresh).verdict, Verdict::kNew);
    ObservedVoxel passing;  // a short peak among views before and after
    for (int s = 0; s < 80; ++s) passing.history.add(s, s >= 38 && s < 42, VoxelHistory::kCapacity);
    EXPECT_EQ(judge_voxel(config, 0.5, passing).verdict, Verdict::kMoving);
    ObservedVoxel sparse;  // a pole hit in every other view: random misses are no change
    for (int s = 0; s < 80; ++s) sparse.history.add(s, s % 2 != 0, VoxelHistory::kCapacity);
    EXPECT_EQ(judge_voxel(config, 0.5, sparse).verdict, Verdict::kStatic);
}

TEST(ChangeDetector, BadConfigurationIsOneLineNamingTheKey) {
    MaintenanceConfig c;
    c.voxel_size = -1.0;
    try {
        LongTermMap map(c);
        FAIL() << "accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("maintenance.voxel_size"), std::string::npos)
            << e.what();
    }
    c = MaintenanceConfig{};
    c.change.gone_hit_fraction = 0.9;
    EXPECT_THROW(LongTermMap{c}, common::ConfigError);
}

TEST(ChangeDetector, EmptyAndNonFiniteScansChangeNothing) {
    LongTermMap map(test_config());
    map.begin_session(0, 0.0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    map.add_scan({}, at(0, 0), 0.0);
    map.add_scan({{nan, 1, 1}, {1, nan, 2}}, at(0, 0), 0.1);
    Eigen::Isometry3d bad = at(0, 0);
    bad.translation().x() = nan;
    map.add_scan({{5, 0, 0}}, bad, 0.2);
    const ChangeSet c = map.end_session();
    EXPECT_EQ(map.stats().voxels, 0u);
    EXPECT_TRUE(c.changes.empty());
}

}  // namespace
}  // namespace ltm::maintenance
