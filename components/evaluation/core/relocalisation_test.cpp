#include "evaluation/core/relocalisation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

RelocAttempt attempt(std::size_t frame, double time, bool has_pose, double dx, double yaw_deg) {
    RelocAttempt a;
    a.frame = frame;
    a.time_s = time;
    a.has_pose = has_pose;
    a.pose.translation() = Eigen::Vector3d(10.0 * frame + dx, 0, 0);
    a.pose.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
    return a;
}

TEST(Relocalisation, HandComputed) {
    common::PoseList ref;
    for (int i = 0; i < 4; ++i) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().x() = 10.0 * i;
        ref.push_back(T);
    }
    const RelocAttempts attempts = {
        attempt(0, 1.0, true, 0.1, 1.0),   // success: 0.1 m, 1 deg
        attempt(1, 2.0, true, 2.0, 0.0),   // wrong: 2 m off
        attempt(2, 3.0, true, 0.0, 10.0),  // wrong: 10 deg off
        attempt(3, 6.0, false, 0, 0),      // gave up
        attempt(9, 1.0, true, 0, 0),       // no reference: excluded
    };
    const RelocResult r = evaluate_relocalisation(attempts, ref);
    EXPECT_EQ(r.attempts, 4u);
    EXPECT_EQ(r.successes, 1u);
    EXPECT_EQ(r.wrong, 2u);
    EXPECT_EQ(r.no_pose, 1u);
    EXPECT_EQ(r.out_of_range, 1u);
    EXPECT_DOUBLE_EQ(r.success_rate, 0.25);
    EXPECT_DOUBLE_EQ(r.time_all_s.mean, 3.0);
    EXPECT_DOUBLE_EQ(r.time_all_s.median, 2.5);
    EXPECT_DOUBLE_EQ(r.time_success_s.mean, 1.0);
    EXPECT_NEAR(r.translation_error.mean, 0.1, 1e-12);
    EXPECT_NEAR(r.rotation_error_deg.mean, 1.0, 1e-9);

    // Looser tolerances: the 10 deg attempt succeeds too.
    RelocConfig loose;
    loose.max_rotation_deg = 15.0;
    EXPECT_DOUBLE_EQ(evaluate_relocalisation(attempts, ref, loose).success_rate, 0.5);
}

}  // namespace
}  // namespace ltm::eval
