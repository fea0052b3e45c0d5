// Which scans maintenance takes (view_spacing.hpp).
#include "maintenance/core/view_spacing.hpp"

#include <gtest/gtest.h>

namespace ltm::maintenance {
namespace {

Eigen::Isometry3d at(double x, double yaw_deg = 0.0) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().x() = x;
    T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
    return T;
}

TEST(ViewSpacing, ByDefaultEveryScanIsTaken) {
    ViewSpacing s;
    for (int i = 0; i < 20; ++i) EXPECT_TRUE(s.take(0.1 * i, at(0.0)));
    EXPECT_EQ(s.taken(), 20u);
    EXPECT_EQ(s.left_out(), 0u);
}

// 2 m/s at 10 Hz (0.2 m a scan) with 0.4 m: every second scan; the distance is from the last
// scan taken, not the last seen.
TEST(ViewSpacing, AScanEveryDistanceDriven) {
    ViewSpacing s({0.4, 10.0, 1.0});
    int taken = 0;
    for (int i = 0; i < 100; ++i) taken += s.take(0.1 * i, at(0.2 * i - 1e-4 * (i % 3)));
    EXPECT_EQ(taken, 50);
    EXPECT_EQ(s.left_out(), 50u);
}

TEST(ViewSpacing, ATurnOnTheSpotIsANewView) {
    ViewSpacing s({0.4, 10.0, 100.0});
    EXPECT_TRUE(s.take(0.0, at(0.0, 0.0)));
    EXPECT_FALSE(s.take(0.1, at(0.0, 6.0)));
    EXPECT_TRUE(s.take(0.2, at(0.0, 12.0)));
    EXPECT_FALSE(s.take(0.3, at(0.0, 20.0)));
}

// Standing still: one scan a second, so what moves around the robot is still seen.
TEST(ViewSpacing, StandingStillTakesAScanEveryInterval) {
    ViewSpacing s({0.4, 10.0, 1.0});
    int taken = 0;
    for (int i = 0; i < 50; ++i) taken += s.take(0.1 * i, at(0.0));  // 5 s
    EXPECT_EQ(taken, 5);
}

// A stamp going back (a new session, a replay) starts over rather than waiting for it.
TEST(ViewSpacing, AStampGoingBackIsTaken) {
    ViewSpacing s({0.4, 10.0, 1.0});
    EXPECT_TRUE(s.take(10.0, at(0.0)));
    EXPECT_FALSE(s.take(10.1, at(0.1)));
    EXPECT_TRUE(s.take(5.0, at(0.1)));
}

TEST(ViewSpacing, BadSettingsAreNamed) {
    EXPECT_FALSE(validate(ViewSpacingConfig{}));
    EXPECT_EQ(*validate({-1.0, 10.0, 1.0}), "view_distance: must be >= 0 (0: every scan)");
    EXPECT_EQ(*validate({0.4, 0.0, 1.0}), "view_angle: must be > 0 [deg]");
    EXPECT_EQ(*validate({0.4, 10.0, 0.0}), "view_interval_s: must be > 0 [s]");
}

}  // namespace
}  // namespace ltm::maintenance
