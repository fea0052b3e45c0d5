// LongTermMap across sessions: what another session on the same ground adds (create_range).
#include "maintenance/core/long_term_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "maintenance/core/test_scene.hpp"

namespace ltm::maintenance {
namespace {

Eigen::Isometry3d pose_at(double x, double y, double yaw_deg) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
    T.translation() = Eigen::Vector3d(x, y, 1.0);
    return T;
}

std::vector<test::Box> scene(double x0) {
    return {{Eigen::Vector3f(float(x0) + 6.0f, 8.0f, 0.0f),
             Eigen::Vector3f(float(x0) + 10.0f, 10.0f, 2.0f), 1},
            {Eigen::Vector3f(float(x0) + 25.0f, -30.0f, 0.0f),
             Eigen::Vector3f(float(x0) + 27.0f, 30.0f, 6.0f), 2}};
}

// A drive of `scans` scans 1 m apart along x from x0, with a lateral offset and a heading (another
// day's pose).
void drive(LongTermMap& map, double x0, double dy, double yaw_deg, double stamp, int scans = 12,
           const std::vector<test::Box>& extra = {}) {
    std::vector<test::Box> boxes = scene(0.0);
    boxes.insert(boxes.end(), extra.begin(), extra.end());
    for (int k = 0; k < scans; ++k) {
        const Eigen::Isometry3d T = pose_at(x0 + 1.0 * k, dy, yaw_deg);
        map.add_scan(test::cast(boxes, T), T, stamp + 0.1 * k);
    }
}

struct Counts {
    std::size_t day0 = 0, day1 = 0;
};

// Day 0 drives x = 0..11; day 1 the same 7 cm to the side and 0.3 deg turned (the far rings land
// between day 0's cells).
Counts repeated_ground(double create_range) {
    MaintenanceConfig c;
    c.view_spacing = 1000.0;  // no views: only what the points create is counted
    c.create_range = create_range;
    LongTermMap map(c);
    map.begin_session(0, 0.0);
    drive(map, 0.0, 0.0, 0.0, 0.0);
    Counts n;
    n.day0 = map.stats().voxels;
    map.begin_session(1, 100.0);
    drive(map, 0.03, 0.07, 0.3, 100.0);
    n.day1 = map.stats().voxels;
    return n;
}

// A view every view_spacing (0.2 s) of a 10 Hz stream whose stamps jitter by a few ms, as a
// driver's do: every second scan, not every second or third as the jitter fell.
TEST(LongTermMapViews, A10HzStreamGivesAViewEveryTwoScans) {
    MaintenanceConfig c;
    c.view_spacing = 0.2;
    LongTermMap map(c);
    map.begin_session(0, 0.0);
    const std::vector<test::Box> boxes = scene(0.0);
    for (int k = 0; k < 60; ++k) {
        const double jitter = 0.002 * double((k * 7) % 3 - 1);  // +-2 ms, a driver's
        const Eigen::Isometry3d T = pose_at(0.2 * k, 0.0, 0.0);
        map.add_scan(test::cast(boxes, T), T, 1000.0 + 0.1 * k + jitter);
    }
    EXPECT_EQ(map.stats().views + map.stats().views_pending, 30u);
}

TEST(LongTermMapGrowth, RepeatedGroundAddsOnlyNearVoxels) {
    const Counts off = repeated_ground(0.0);
    const Counts on = repeated_ground(15.0);
    EXPECT_EQ(on.day0, off.day0);  // a first session creates everywhere
    const double grown_off = double(off.day1 - off.day0) / double(off.day0);
    const double grown_on = double(on.day1 - on.day0) / double(on.day0);
    std::printf(
        "voxels %zu -> %zu (+%.1f %%) without, %zu -> %zu (+%.1f %%) with create_range 15\n",
        off.day0, off.day1, 100.0 * grown_off, on.day0, on.day1, 100.0 * grown_on);
    EXPECT_GT(grown_off, 0.05);  // without the bound another day's far rings add voxels
    EXPECT_LT(grown_on, 0.02);   // with it the same ground grows by under 2 %
    EXPECT_LT(grown_on, grown_off / 4.0);
}

TEST(LongTermMapGrowth, NewGroundCreatesEverywhere) {
    // Day 1 drives the same ground, then ground 400 m away that no session mapped: its far
    // voxels are all created, as on a first session.
    auto run = [](double create_range) {
        MaintenanceConfig c;
        c.view_spacing = 1000.0;
        c.create_range = create_range;
        LongTermMap map(c);
        map.begin_session(0, 0.0);
        drive(map, 0.0, 0.0, 0.0, 0.0);
        map.begin_session(1, 100.0);
        drive(map, 0.03, 0.07, 0.3, 100.0);
        const std::size_t before = map.stats().voxels;
        drive(map, 400.0, 0.0, 0.0, 110.0);
        return map.stats().voxels - before;
    };
    const std::size_t off = run(0.0), on = run(15.0);
    EXPECT_GT(off, 1000u);
    EXPECT_EQ(on, off);
}

TEST(LongTermMapGrowth, ANewObjectFarAwayIsCreatedAboveTheGround) {
    // Day 1 a 2 m box stands 17-20 m from the route on ground day 0 mapped: the cells beside
    // day 0's ground (its lowest 0.5 m) wait for a nearer view, the rest are created as without
    // the bound.
    const test::Box box{Eigen::Vector3f(3.0f, 17.0f, 0.0f), Eigen::Vector3f(6.0f, 20.0f, 2.0f), 3};
    auto run = [&](double create_range) {
        MaintenanceConfig c;
        c.view_spacing = 1000.0;
        c.create_range = create_range;
        LongTermMap map(c);
        map.begin_session(0, 0.0);
        drive(map, 0.0, 0.0, 0.0, 0.0);
        map.begin_session(1, 100.0);
        drive(map, 0.03, 0.07, 0.3, 100.0, 12, {box});
        std::size_t above = 0, low = 0;
        for (const Eigen::Vector3f& p : map.voxel_centres()) {
            if (p.x() < 2.9f || p.x() > 6.1f || p.y() < 16.9f || p.y() > 20.1f) continue;
            (p.z() > 0.5f ? above : low)++;
        }
        return std::make_pair(above, low);
    };
    const auto off = run(0.0), on = run(15.0);
    EXPECT_GT(off.first, 100u);
    EXPECT_EQ(on.first, off.first);
    EXPECT_LE(on.second, off.second);
}

TEST(LongTermMapGrowth, FarPointsStillAddToTheirVoxels) {
    MaintenanceConfig c;
    c.view_spacing = 1000.0;
    c.create_range = 15.0;
    LongTermMap map(c);
    map.begin_session(0, 0.0);
    drive(map, 0.0, 0.0, 0.0, 0.0);
    // The wall's face is at x = 25; day 1 sees it only from 22-25 m, beyond create_range.
    const Eigen::Vector3f face(25.05f, 0.1f, 1.1f);
    const ObservedVoxel* v = map.voxel_at(face);
    ASSERT_NE(v, nullptr);
    const auto points_day0 = v->points.count;
    map.begin_session(1, 100.0);
    const std::size_t voxels = map.stats().voxels;
    drive(map, 0.0, 0.0, 0.0, 100.0, 4);  // day 0's first poses: the same cells
    v = map.voxel_at(face);
    ASSERT_NE(v, nullptr);
    EXPECT_GT(v->points.count, points_day0);
    EXPECT_EQ(map.stats().voxels, voxels);
}

}  // namespace
}  // namespace ltm::maintenance
