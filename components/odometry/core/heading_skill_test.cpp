#include "odometry/core/heading_skill.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "odometry/core/motion_model.hpp"

namespace ltm::odometry {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d pose(double x, double y, double yaw_deg) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = registration::so3_exp(Eigen::Vector3d(0, 0, yaw_deg * kDeg));
    T.translation() = Eigen::Vector3d(x, y, 0);
    return T;
}

// A handheld sensor's sparse keyframes swing left and right (hku-avia every 5th keyframe: +33,
// -38, -31, +50 deg a step): extrapolating the last turn misses by the sum of two swings, holding
// the heading by one. After a few such scans the skill holds the heading.
TEST(HeadingSkill, HoldsTheHeadingWhereTheTurnRateMissesASwingingStream) {
    HeadingSkill skill(0.8);
    const double yaw[] = {0, 33, -5, 45, 7, 40, 2};  // heading a scan [deg]
    for (int i = 2; i < 7; ++i) {
        EXPECT_EQ(skill.hold(), i >= 2 + HeadingSkill::kMinScans) << "scan " << i;
        const double extrapolated = 2 * yaw[i - 1] - yaw[i - 2];
        skill.observe(std::abs(extrapolated - yaw[i]) * kDeg, std::abs(yaw[i - 1] - yaw[i]) * kDeg);
    }
    EXPECT_TRUE(skill.hold());
    EXPECT_LT(skill.held_error(), 0.8 * skill.extrapolated_error());
}

// A car's corner: the turn rate goes on, the held heading lags; never held. Ratio 0: never.
TEST(HeadingSkill, KeepsTheTurnRateForASteadyTurnAndWhenOff) {
    HeadingSkill skill(0.8), off(0.0);
    for (int i = 0; i < 10; ++i) {
        skill.observe(1.0 * kDeg, 6.0 * kDeg);
        off.observe(30.0 * kDeg, 1.0 * kDeg);
    }
    EXPECT_FALSE(skill.hold());
    EXPECT_FALSE(off.hold());
}

// The held prediction: the last pose's rotation, the last step's translation in odometry axes
// scaled to the time (not turned with the turn rate).
TEST(HeadingSkill, TheHeldPredictionKeepsTheLastHeadingAndTheStepInOdometryAxes) {
    MotionModel m;
    m.push(0.0, pose(0, 0, 0));
    m.push(2.0, pose(1, 0, 40));
    const Eigen::Isometry3d held = m.predict_heading_held(3.0);
    EXPECT_TRUE(held.linear().isApprox(pose(1, 0, 40).linear(), 1e-12));
    EXPECT_TRUE(held.translation().isApprox(Eigen::Vector3d(1.5, 0, 0), 1e-12));
    // The constant turn rate turns the step: it predicts elsewhere.
    EXPECT_GT((m.predict(3.0).translation() - held.translation()).norm(), 0.1);
}

}  // namespace
}  // namespace ltm::odometry
