// The spin hold (issue 27, spin_hold.hpp): a narrow sensor that walks, stops and turns on the spot
// keeps its position along the directions its scans cannot observe instead of going on with the
// walk's velocity.
#include "odometry/core/spin_hold.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "odometry/core/odometry.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
constexpr double kPeriod = 0.1;  // [s] scans at 10 Hz

TEST(SpinHold, HoldAlongMovesOnlyAlongTheGivenDirections) {
    Isometry3d pose = Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.7, Vector3d::UnitZ()).matrix();
    pose.translation() = Vector3d(3.0, -2.0, 0.5);
    const Isometry3d before = pose;
    // Along x and along a direction nearly the same (one span), held at the anchor's x.
    const double moved = hold_along(Vector3d(1.0, 5.0, 7.0),
                                    {Vector3d(2.0, 0.0, 0.0), Vector3d(1.0, 1e-12, 0.0)}, &pose);
    EXPECT_NEAR(moved, 2.0, 1e-9);
    EXPECT_NEAR((pose.translation() - Vector3d(1.0, -2.0, 0.5)).norm(), 0.0, 1e-9);
    EXPECT_TRUE(pose.linear().isApprox(before.linear()));
    // A plane (x and y): only z stays.
    pose = before;
    hold_along(Vector3d(1.0, 5.0, 7.0), {Vector3d::UnitX(), Vector3d(1.0, 1.0, 0.0)}, &pose);
    EXPECT_NEAR((pose.translation() - Vector3d(1.0, 5.0, 0.5)).norm(), 0.0, 1e-9);
    // Nothing to hold.
    pose = before;
    EXPECT_EQ(hold_along(Vector3d::Zero(), {}, &pose), 0.0);
    EXPECT_TRUE(pose.isApprox(before));
}

TEST(SpinHold, TheRecentTurnRateFollowsTheStepsOverItsWindow) {
    Isometry3d a = Isometry3d::Identity();
    Isometry3d b = a;
    b.linear() = Eigen::AngleAxisd(10.0 * M_PI / 180.0, Vector3d::UnitZ()).matrix();
    EXPECT_NEAR(turn_rate(a, b, 0.1), 100.0, 1e-9);
    EXPECT_EQ(turn_rate(a, b, 0.0), 0.0);
    RecentTurnRate r;
    for (int i = 0; i < 5; ++i) r.add(100.0, 0.1, 0.5);  // 0.5 s at 100 deg/s
    EXPECT_NEAR(r.rate(), 100.0 * (1.0 - std::exp(-1.0)), 1e-9);
    r.add(0.0, 0.1, 0.5);  // a fit that lost the turn lowers it, it does not reset it
    EXPECT_GT(r.rate(), 45.0);
    r.add(1e9, 0.0, 0.5);  // no time passed: ignored
    EXPECT_LT(r.rate(), 100.0);
}

// A hall 8 m wide and 4 m high, 120 m long along x, closed by an end wall at x = 20; the sensor
// stands on its axis, 100 m from its open end (beyond the sensor's range). Plain walls: facing a
// side wall or the open end a scan observes y, z and the rotation, never x.
registration::test::Scene hall_scene() {
    registration::test::Scene s;
    s.add_quad({-40, 0, 0}, {60, 0, 0}, {0, 4, 0});
    s.add_quad({-40, 0, 4}, {60, 0, 0}, {0, 4, 0});
    s.add_quad({-40, -4, 2}, {60, 0, 0}, {0, 0, 2});
    s.add_quad({-40, 4, 2}, {60, 0, 0}, {0, 0, 2});
    s.add_quad({20, 0, 2}, {0, 4, 0}, {0, 0, 2});
    return s;
}

// A narrow sensor: the points of a spinning LiDAR within +-35 deg of its x axis (a Livox-like
// view), with their times.
common::PointCloud narrow(const common::PointCloud& c) {
    common::PointCloud out;
    out.stamp = c.stamp;
    for (std::size_t i = 0; i < c.size(); ++i) {
        const Eigen::Vector3f& p = c.points[i];
        if (std::abs(std::atan2(p.y(), p.x())) > 35.0 * M_PI / 180.0) continue;
        out.points.push_back(p);
        if (c.has_time()) out.time.push_back(c.time[i]);
    }
    return out;
}

// Walks toward the end wall at 2 m/s for 1 s, stops and turns on the spot at 120 deg/s for 3 s:
// facing the side walls or the open end, the scans cannot observe x. Returns the largest distance
// of the odometry's position from the truth's while it turns (the truth does not move then).
double drift_through_the_spin(const OdometryConfig& config, std::vector<FrameResult>* results) {
    const registration::test::Scene scene = hall_scene();
    const auto truth = [](double t) {
        const double walk = std::min(t, 1.0);
        const double yaw = t < 1.0 ? 0.0 : 2.0 * M_PI / 3.0 * (t - 1.0);  // 120 deg/s
        Isometry3d T = registration::test::make_pose(-2.0 + 2.0 * walk, 0.0, 1.5, 0, 0, 0);
        T.linear() = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).matrix();
        return T;
    };
    registration::test::ScanPattern pattern;
    pattern.rings = 40;  // +-35 deg: a Livox Avia's vertical field (77 deg)
    pattern.fov_up = 35.0;
    pattern.fov_down = -35.0;
    pattern.azimuths = 1440;
    pattern.period = kPeriod;
    Odometry odo(config, truth(0.0));
    double worst = 0.0;
    for (int i = 0; i < 40; ++i) {
        const double t = kPeriod * i;
        common::PointCloud c = narrow(registration::test::scan_scene(
            scene, pattern, truth(t), truth(t + kPeriod), 300 + i, true));
        c.stamp = t;
        results->push_back(odo.register_frame(c));
        if (t > 1.0) {
            worst = std::max(
                worst,
                (results->back().T_odom_lidar.translation() - truth(t).translation()).norm());
        }
    }
    return worst;
}

TEST(SpinHold, ANarrowSensorTurningOnTheSpotStaysOnItsSpot) {
    const OdometryConfig narrow_preset = preset_config(common::SensorPreset::kNarrow);
    std::vector<FrameResult> held;
    const double worst = drift_through_the_spin(narrow_preset, &held);
    int degenerate = 0, holds = 0;
    for (const FrameResult& r : held) {
        degenerate += r.status == FrameStatus::kDegenerate;
        holds += r.spin_hold;
        if (r.spin_hold) {
            EXPECT_GE(r.turn_rate, narrow_preset.tracking.spin_rate);
        }
    }
    EXPECT_GT(degenerate, 10);  // the narrow view of the hall cannot observe x in most of the turn
    EXPECT_GT(holds, 10);
    // 1.74 m: the turn's rotation is lost after 130 deg (degenerate scans stay out of the map,
    // which then holds nothing of the new view), but the position stays near the spot.
    EXPECT_LT(worst, 3.0);
    // Without the hold (tracking.spin_rate 0, as before it) the walk's velocity and the slides of
    // the weak fits go on along the unobserved x: 5.56 m.
    OdometryConfig off = narrow_preset;
    off.tracking.spin_rate = 0.0;
    std::vector<FrameResult> free;
    const double drift = drift_through_the_spin(off, &free);
    for (const FrameResult& r : free) EXPECT_FALSE(r.spin_hold);
    EXPECT_GT(drift, 4.0);
    std::printf("spin hold: worst %.3f m; without it %.3f m\n", worst, drift);
}

}  // namespace
}  // namespace ltm::odometry
