#include "odometry/core/motion_model.hpp"

#include <gtest/gtest.h>

namespace ltm::odometry {
namespace {

Eigen::Isometry3d pose(double x, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = registration::so3_exp(Eigen::Vector3d(0, 0, yaw));
    T.translation() = Eigen::Vector3d(x, 0.5 * x, 0);
    return T;
}

TEST(MotionModel, PredictsTheLastPoseUntilItHasTwo) {
    MotionModel m;
    EXPECT_TRUE(m.predict(1.0).isApprox(Eigen::Isometry3d::Identity()));
    m.push(0.0, pose(1, 0.1));
    EXPECT_TRUE(m.predict(0.1).isApprox(pose(1, 0.1)));
    EXPECT_TRUE(m.velocity().isZero());
}

TEST(MotionModel, ConstantVelocityScaledByTime) {
    MotionModel m;
    const Eigen::Isometry3d a = pose(0, 0), b = pose(1, 0.1);
    m.push(0.0, a);
    m.push(0.1, b);
    const Eigen::Isometry3d delta = a.inverse() * b;
    EXPECT_TRUE(m.predict(0.2).isApprox(b * delta, 1e-12));
    // A dropped frame: twice the time, twice the motion.
    EXPECT_TRUE(m.predict(0.3).isApprox(b * delta * delta, 1e-12));
    EXPECT_TRUE(m.velocity().isApprox(registration::se3_log(delta) / 0.1, 1e-12));
}

// Down a corridor (x unobservable) the motion along the way of travel goes on; a sideways
// velocity along an unobservable direction dies out (damped by `keep`).
TEST(MotionModel, DampingKeepsTheWayOfTravelAndDampsSideways) {
    const auto straight = [](double x, double y) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(x, y, 0);
        return T;
    };
    registration::Vector6d along = registration::Vector6d::Zero(), side = along;
    along(0) = 1.0;
    side(1) = 1.0;
    MotionModel m;
    m.push(0.0, straight(0, 0));
    m.push(0.1, straight(1.0, 0.1));
    m.damp({along, side}, 1.0, 0.5, 1.0, 0.05);
    const Eigen::Vector3d step = m.predict(0.2).translation() - Eigen::Vector3d(1.0, 0.1, 0);
    EXPECT_NEAR(step.x(), 1.0, 1e-9);   // travel: kept
    EXPECT_NEAR(step.y(), 0.05, 1e-9);  // sideways: halved
    // travel_keep below 1 damps the way of travel too.
    MotionModel n;
    n.push(0.0, straight(0, 0));
    n.push(0.1, straight(1.0, 0));
    n.damp({along}, 1.0, 0.5, 0.5, 0.05);
    EXPECT_NEAR(n.predict(0.2).translation().x() - 1.0, 0.5, 1e-9);
}

// A last step that turns (10 deg, a robot turning on the spot while its walk is unobservable) is
// no travel: the walk along the unobservable direction dies out instead of being carried through
// the spin.
TEST(MotionModel, ATurningStepIsNoTravel) {
    Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = a;
    b.translation() = Eigen::Vector3d(1.0, 0, 0);
    b.linear() =
        Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    registration::Vector6d along = registration::Vector6d::Zero();
    along(0) = 1.0;
    MotionModel m;
    m.push(0.0, a);
    m.push(0.1, b);
    m.damp({along}, 1.0, 0.5, 1.0, 3.0 * M_PI / 180.0);
    EXPECT_NEAR(m.velocity()(0) * 0.1, 0.5, 0.02);  // halved, not kept
    MotionModel n;  // the same with a turn allowed up to 20 deg: travel, kept
    n.push(0.0, a);
    n.push(0.1, b);
    n.damp({along}, 1.0, 0.5, 1.0, 20.0 * M_PI / 180.0);
    EXPECT_NEAR(n.velocity()(0) * 0.1, 1.0, 0.02);
}

TEST(MotionModel, VelocityIsTakenBetweenTheMidSweepPoses) {
    // Scans de-skewed with different velocities: their poses at the stamps differ by what each
    // de-skew assumed; the poses at the middle of the sweeps (where registration fixes a de-skewed
    // scan) give the velocity.
    const Eigen::Isometry3d mid_a = pose(0, 0), mid_b = pose(1, 0.1), mid_c = pose(2.5, 0.3);
    const Eigen::Isometry3d stamp_mid_a = pose(0.2, 0.05), stamp_mid_b = pose(0.7, -0.02);
    MotionModel m;
    m.push(0.0, mid_a * stamp_mid_a.inverse(), stamp_mid_a);
    EXPECT_TRUE(m.velocity_to(0.1, mid_b)
                    .isApprox(registration::se3_log(mid_a.inverse() * mid_b) / 0.1, 1e-12));
    m.push(0.1, mid_b * stamp_mid_b.inverse(), stamp_mid_b);
    EXPECT_TRUE(m.last_pose().isApprox(mid_b * stamp_mid_b.inverse(), 1e-12));
    EXPECT_TRUE(m.velocity().isApprox(registration::se3_log(mid_a.inverse() * mid_b) / 0.1, 1e-12));
    EXPECT_TRUE(m.velocity_to(0.3, mid_c)
                    .isApprox(registration::se3_log(mid_b.inverse() * mid_c) / 0.2, 1e-12));
    EXPECT_TRUE(m.velocity_to(0.1, mid_c).isZero());  // no time has passed
}

TEST(MotionModel, FrameAndNoneModesIgnoreTheStamps) {
    const Eigen::Isometry3d a = pose(0, 0), b = pose(1, 0.1);
    MotionModel frame(PredictionMode::kFrame), none(PredictionMode::kNone);
    for (MotionModel* m : {&frame, &none}) {
        m->push(0.0, a);
        m->push(7.3, b);  // irregular stamps, as in a keyframe stream
    }
    EXPECT_TRUE(frame.predict(7.7).isApprox(b * (a.inverse() * b), 1e-12));
    EXPECT_TRUE(none.predict(7.7).isApprox(b));
}

TEST(MotionModel, RepeatedExtrapolationStaysARigidTransform) {
    MotionModel m(PredictionMode::kFrame);
    m.push(0.0, pose(0, 0));
    m.push(0.1, pose(1, 0.3));
    for (int i = 2; i < 2000; ++i) m.push(0.1 * i, m.predict(0.1 * i));
    const Eigen::Matrix3d R = m.last_pose().linear();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-9);
    EXPECT_TRUE(m.last_pose().matrix().allFinite());
}

}  // namespace
}  // namespace ltm::odometry
