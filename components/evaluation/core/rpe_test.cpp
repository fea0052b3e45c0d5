#include "evaluation/core/rpe.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

Eigen::Isometry3d pose(double x, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).matrix();
    T.translation() = Eigen::Vector3d(x, 0, 0);
    return T;
}

TEST(Rpe, HandComputedTranslationSteps) {
    // Steps of 1, 1.1, 1 m against 1 m: errors 0, 0.1, 0.
    const common::PoseList ref{pose(0, 0), pose(1, 0), pose(2, 0), pose(3, 0)};
    const common::PoseList est{pose(0, 0), pose(1, 0), pose(2.1, 0), pose(3.1, 0)};
    const RpeResult r = compute_rpe(est, ref);
    EXPECT_EQ(r.translation.n, 3u);
    EXPECT_NEAR(r.translation.max, 0.1, 1e-12);
    EXPECT_NEAR(r.translation.mean, 0.1 / 3.0, 1e-12);
    EXPECT_NEAR(r.translation.rmse, std::sqrt(0.01 / 3.0), 1e-12);
    EXPECT_NEAR(r.rotation_deg.max, 0.0, 1e-12);
    // Over 3 frames: one pair, error 0.1.
    EXPECT_NEAR(compute_rpe(est, ref, 3).translation.rmse, 0.1, 1e-12);
}

TEST(Rpe, HandComputedRotationStep) {
    // A 0.1 rad yaw error appears between frames 1 and 2. Pair (1,2): rotation error 0.1 rad,
    // translation 0. Pair (2,3): the estimate looks 0.1 rad off the direction of travel, so its
    // 1 m step lands 2 sin(0.05) m from the true one, with no rotation error.
    const common::PoseList ref{pose(0, 0), pose(1, 0), pose(2, 0), pose(3, 0)};
    const common::PoseList est{pose(0, 0), pose(1, 0), pose(2, 0.1), pose(3, 0.1)};
    std::vector<double> t, a;
    rpe_errors(est, ref, 1, t, a);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_NEAR(a[1], 0.1 * 180.0 / M_PI, 1e-9);
    EXPECT_NEAR(t[1], 0.0, 1e-12);
    EXPECT_NEAR(a[2], 0.0, 1e-9);
    EXPECT_NEAR(t[2], 2.0 * std::sin(0.05), 1e-12);
}

TEST(Rpe, RotationAngleIsAccurateNearZeroAndPi) {
    for (double angle : {1e-7, 0.3, 3.0, M_PI - 1e-6}) {
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
        EXPECT_NEAR(rotation_angle(R), angle, 1e-9);
    }
}

TEST(Rpe, TooFewPosesGiveEmptyStats) {
    const common::PoseList one{pose(0, 0)};
    EXPECT_EQ(compute_rpe(one, one).translation.n, 0u);
}

}  // namespace
}  // namespace ltm::eval
