// Motion across the scans of a short window: ray-cast scenes with exact ground truth (a walker
// beside a wall, a parked car, a passing sensor).
#include "maintenance/core/motion_tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <tuple>

#include "common/core/config_check.hpp"
#include "maintenance/core/long_term_map.hpp"
#include "maintenance/core/test_scene.hpp"

namespace ltm::maintenance {
namespace {

using test::Box;
using test::cast;

constexpr int kWalker = 7, kCar = 3, kWall = 1;

Eigen::Isometry3d sensor_at(double x, double y) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, 1.0);
    return T;
}

// A street: a wall along y = 1.5, a parked car, a walker 1 m in front of the wall walking 1 m
// along it in 1 s; the sensor (a car) drives past at `sensor_speed` m/s. Scan k at 0.1 k s.
std::vector<Box> street(double time) {
    const float x = float(4.0 + 1.0 * time);  // the walker's rear edge
    return {{{-30.0f, 1.5f, 0.0f}, {30.0f, 1.8f, 3.0f}, kWall},
            {{-6.0f, -1.0f, 0.0f}, {-1.5f, 0.8f, 1.5f}, kCar},
            {{x, 0.0f, 0.0f}, {x + 0.5f, 0.5f, 1.7f}, kWalker}};
}

struct Window {
    std::size_t walker = 0, walker_reported = 0, reported_on_walker = 0, static_reported = 0,
                reported = 0;
};

bool inside(const Eigen::Vector3f& p, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
            float pad) {
    return (p.array() >= lo.array() - pad).all() && (p.array() <= hi.array() + pad).all();
}

Window run_tracker(double sensor_speed) {
    MotionTracker tracker(MotionConfig{}, RangeImageConfig{}, 50.0);
    Window w;
    const std::vector<Box> fixed = street(0.0);
    for (int k = 0; k <= 10; ++k) {
        const double t = 0.1 * k;
        const Eigen::Isometry3d T = sensor_at(-10.0 + sensor_speed * t, -9.0);
        std::vector<int> ids;
        const std::vector<Eigen::Vector3f> pts = cast(street(t), T, &ids);
        // Above its feet: the feet are the scan's ground (ground_height) and stay with it.
        for (std::size_t i = 0; i < pts.size(); ++i)
            w.walker += ids[i] == kWalker && (T.cast<float>() * pts[i]).z() > 0.4f ? 1 : 0;
        for (const Eigen::Vector3f& p : tracker.add_scan(pts, T, t)) {
            ++w.reported;
            // Anywhere the walker was during the second, or the ground in its cells' columns
            // (its feet leave with it); never on the car or the wall.
            const Eigen::Vector3f lo(4.0f, 0.0f, 0.0f), hi(5.5f, 0.5f, 1.7f);
            if (inside(p, lo, hi, 0.05f) || (p.z() < 0.05f && inside(p, lo, hi, 0.25f))) {
                ++w.reported_on_walker;
                w.walker_reported += p.z() > 0.4f ? 1 : 0;
            }
            if (inside(p, fixed[0].lo, fixed[0].hi, 0.05f) ||
                inside(p, fixed[1].lo, fixed[1].hi, 0.05f))
                ++w.static_reported;
        }
    }
    return w;
}

TEST(MotionTracker, AWalkerMovingOneMetreInOneSecondIsMovingTheParkedCarIsNot) {
    for (const double speed : {0.0, 8.0}) {  // the sensor parked, and driving past at 8 m/s
        const Window w = run_tracker(speed);
        ASSERT_GT(w.walker, 200u) << "speed " << speed;
        EXPECT_GE(w.walker_reported, w.walker * 8 / 10)
            << "speed " << speed << ": " << w.walker_reported << " of " << w.walker;
        EXPECT_EQ(w.static_reported, 0u) << "speed " << speed;
        EXPECT_EQ(w.reported, w.reported_on_walker) << "speed " << speed;
    }
}

TEST(MotionTracker, ParkedCarPassedAtSpeedIsNotMoving) {
    // Only static things, passed at 15 m/s: the car's visible side changes, its place does not.
    MotionTracker tracker(MotionConfig{}, RangeImageConfig{}, 50.0);
    const std::vector<Box> scene = {
        street(0.0)[0], street(0.0)[1], {{8.0f, -3.0f, 0.0f}, {12.5f, -1.2f, 1.6f}, kCar}};
    std::size_t reported = 0;
    for (int k = 0; k <= 20; ++k) {
        const Eigen::Isometry3d T = sensor_at(-15.0 + 1.5 * k, -6.0);
        reported += tracker.add_scan(cast(scene, T), T, 0.1 * k).size();
    }
    EXPECT_EQ(reported, 0u);
    EXPECT_GT(tracker.stats().compared, 10u);  // the cars were compared, and kept
}

TEST(MotionTracker, ItsVoxelsLeaveTheMapStaticOnesStay) {
    // Through the long-term map with its defaults (no preset): the walker's voxels go, the wall's
    // and the car's stay; without the motion tracker the walker, hit in its views, stays, and so
    // it does when the tracker follows only the session's first 0.3 s (motion.session_span).
    const auto run = [](bool enabled, double span, std::size_t* walker, std::size_t* walker_kept,
                        std::size_t* stat, std::size_t* stat_kept) {
        MaintenanceConfig config;
        config.motion.enabled = enabled;
        config.motion.session_span = span;
        LongTermMap map(config);
        std::set<std::tuple<int, int, int>> moving, still;
        const float s = float(config.voxel_size);
        for (int k = 0; k <= 10; ++k) {
            const double t = 0.1 * k;
            const Eigen::Isometry3d T = sensor_at(-10.0 + 8.0 * t, -9.0);
            std::vector<int> ids;
            const std::vector<Eigen::Vector3f> pts = cast(street(t), T, &ids);
            map.add_scan(pts, T, 100.0 + t);
            for (std::size_t i = 0; i < pts.size(); ++i) {
                const Eigen::Vector3f w = T.cast<float>() * pts[i];
                const std::tuple<int, int, int> c{int(std::floor(w.x() / s)),
                                                  int(std::floor(w.y() / s)),
                                                  int(std::floor(w.z() / s))};
                if (ids[i] == kWalker && w.z() > 0.3f) moving.insert(c);
                if (ids[i] == kCar || ids[i] == kWall) still.insert(c);
            }
        }
        map.end_session();
        const auto kept = [&](const std::set<std::tuple<int, int, int>>& cells) {
            std::size_t n = 0;
            for (const auto& [x, y, z] : cells)
                n += map.keeps({(x + 0.5f) * s, (y + 0.5f) * s, (z + 0.5f) * s}) ? 1 : 0;
            return n;
        };
        for (const auto& c : moving) still.erase(c);
        *walker = moving.size();
        *walker_kept = kept(moving);
        *stat = still.size();
        *stat_kept = kept(still);
    };
    std::size_t walker = 0, walker_kept = 0, stat = 0, stat_kept = 0;
    run(true, 12.0, &walker, &walker_kept, &stat, &stat_kept);
    ASSERT_GT(walker, 30u);
    ASSERT_GT(stat, 300u);
    EXPECT_LE(walker_kept, walker / 10) << walker_kept << " of " << walker << " kept";
    EXPECT_GE(stat_kept, stat * 99 / 100) << stat_kept << " of " << stat << " kept";
    run(false, 12.0, &walker, &walker_kept, &stat, &stat_kept);
    EXPECT_GT(walker_kept, walker / 2) << walker_kept << " of " << walker << " kept without it";
    run(true, 0.3, &walker, &walker_kept, &stat, &stat_kept);
    EXPECT_GT(walker_kept, walker / 2) << walker_kept << " of " << walker << " kept past the span";
}

// SemanticKITTI 07's walker: 0.3 m in front of a hedge 14 m long, on the cells next to the
// hedge's (0.2 m cells: a gap of one cell's width is bridged by cell adjacency alone), walking 1 m
// along it in 1 s; a reflection 3.6 m below the road beside it (KITTI's multipath returns).
constexpr int kHedge = 2;
std::vector<Box> hedge_street(double time) {
    const float x = float(4.0 + 1.0 * time);
    return {{{-3.0f, 0.78f, 0.0f}, {11.0f, 1.6f, 1.5f}, kHedge},
            {{x, 0.0f, 0.0f}, {x + 0.5f, 0.48f, 1.7f}, kWalker}};
}

struct HedgeWindow {
    std::size_t walker = 0, walker_reported = 0, hedge_reported = 0, reported = 0;
};

HedgeWindow run_hedge(const MotionConfig& config, double sensor_speed, bool reflection) {
    MotionTracker tracker(config, RangeImageConfig{}, 50.0);
    HedgeWindow w;
    const Box hedge = hedge_street(0.0)[0];
    for (int k = 0; k <= 10; ++k) {
        const double t = 0.1 * k;
        // On the road 2.5 m beside the hedge's line, behind the walker (07's view of it).
        const Eigen::Isometry3d T = sensor_at(-10.0 + sensor_speed * t, -2.5);
        std::vector<int> ids;
        std::vector<Eigen::Vector3f> pts = cast(hedge_street(t), T, &ids);
        for (std::size_t i = 0; i < pts.size(); ++i)
            w.walker += ids[i] == kWalker && (T.cast<float>() * pts[i]).z() > 0.4f ? 1 : 0;
        if (reflection)
            for (const float dx : {0.0f, 0.05f, 0.1f, 0.15f})
                pts.push_back(T.inverse().cast<float>() * Eigen::Vector3f(5.0f + dx, -0.6f, -3.6f));
        for (const Eigen::Vector3f& p : tracker.add_scan(pts, T, t)) {
            ++w.reported;
            if (inside(p, {4.0f, 0.0f, 0.0f}, {5.5f, 0.48f, 1.7f}, 0.05f))
                w.walker_reported += p.z() > 0.4f ? 1 : 0;
            if (inside(p, hedge.lo, hedge.hi, 0.02f)) ++w.hedge_reported;
        }
    }
    return w;
}

TEST(MotionTracker, AWalkerBesideAHedgeIsMovingTheHedgeIsNot) {
    for (const double speed : {0.0, 5.0}) {
        for (const bool reflection : {false, true}) {
            const HedgeWindow w = run_hedge(MotionConfig{}, speed, reflection);
            const std::string at = "speed " + std::to_string(speed) +
                                   (reflection ? ", a reflection below the road" : "");
            ASSERT_GT(w.walker, 150u) << at;
            EXPECT_GE(w.walker_reported, w.walker * 8 / 10)
                << at << ": " << w.walker_reported << " of " << w.walker;
            EXPECT_EQ(w.hedge_reported, 0u) << at;
        }
    }
    // Joined whatever the gap between their cells' points (the rule before join_distance), the
    // walker is part of a 14 m cluster, not an object, and is never followed.
    MotionConfig joined;
    joined.join_distance = 1.0;
    const HedgeWindow w = run_hedge(joined, 5.0, false);
    EXPECT_LT(w.walker_reported, w.walker / 10) << w.walker_reported << " of " << w.walker;
}

TEST(MotionTracker, TheWalkerBesideTheHedgeLeavesTheMapTheHedgeStays) {
    // Through the long-term map with its defaults: the hedge's voxels are hit in every view and
    // never in a moving cluster; the walker's leave.
    MaintenanceConfig config;
    LongTermMap map(config);
    std::set<std::tuple<int, int, int>> walker, hedge;
    const float s = float(config.voxel_size);
    for (int k = 0; k <= 10; ++k) {
        const double t = 0.1 * k;
        const Eigen::Isometry3d T = sensor_at(-10.0 + 5.0 * t, -2.5);
        std::vector<int> ids;
        const std::vector<Eigen::Vector3f> pts = cast(hedge_street(t), T, &ids);
        map.add_scan(pts, T, 100.0 + t);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const Eigen::Vector3f w = T.cast<float>() * pts[i];
            const std::tuple<int, int, int> c{
                int(std::floor(w.x() / s)), int(std::floor(w.y() / s)), int(std::floor(w.z() / s))};
            if (ids[i] == kWalker && w.z() > 0.3f) walker.insert(c);
            if (ids[i] == kHedge) hedge.insert(c);
        }
    }
    map.end_session();
    for (const auto& c : walker) hedge.erase(c);  // voxels both touch are neither's
    const auto kept = [&](const std::set<std::tuple<int, int, int>>& cells) {
        std::size_t n = 0;
        for (const auto& [x, y, z] : cells)
            n += map.keeps({(x + 0.5f) * s, (y + 0.5f) * s, (z + 0.5f) * s}) ? 1 : 0;
        return n;
    };
    ASSERT_GT(walker.size(), 20u);
    ASSERT_GT(hedge.size(), 300u);
    EXPECT_LE(kept(walker), walker.size() / 5) << kept(walker) << " of " << walker.size();
    EXPECT_GE(kept(hedge), hedge.size() * 99 / 100) << kept(hedge) << " of " << hedge.size();
}

TEST(MotionTracker, BadKeysAreOneLineNamingTheKey) {
    MaintenanceConfig c;
    c.motion.min_lag = 2.0;  // above max_lag
    try {
        LongTermMap map(c);
        FAIL() << "accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("motion.min_lag"), std::string::npos) << e.what();
    }
    c = MaintenanceConfig{};
    c.motion.cell = 0.0;
    EXPECT_THROW(LongTermMap{c}, common::ConfigError);
}

TEST(MotionTracker, OddInputFindsNothing) {
    MotionTracker tracker(MotionConfig{}, RangeImageConfig{}, 50.0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(tracker.add_scan({}, sensor_at(0, 0), 0.0).empty());
    EXPECT_TRUE(tracker.add_scan({{nan, 1.0f, 0.0f}}, sensor_at(0, 0), 0.1).empty());
    Eigen::Isometry3d bad = sensor_at(0, 0);
    bad(0, 3) = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(tracker.add_scan(cast(street(0.2), sensor_at(0, -9)), bad, 0.2).empty());
    // Time going back: the kept scans are forgotten, not compared.
    EXPECT_TRUE(
        tracker.add_scan(cast(street(1.0), sensor_at(0, -9)), sensor_at(0, -9), 5.0).empty());
    EXPECT_TRUE(
        tracker.add_scan(cast(street(0.0), sensor_at(0, -9)), sensor_at(0, -9), 4.0).empty());
}

}  // namespace
}  // namespace ltm::maintenance
