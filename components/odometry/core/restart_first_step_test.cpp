// A restart's first step (issue 27): after a gap the odometry restarts in a new segment whose map
// holds one scan, at a prediction carrying the velocity from before the gap. The next scan of a
// sparse stream fits that one-scan map from that guess, several metres off: it gets the forward
// search a run's first step gets, and is never reported registered while metres off.
#include <gtest/gtest.h>

#include <string>

#include "odometry/core/odometry.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Isometry3d;

Isometry3d street(double x) { return registration::test::make_pose(x, 0.0, 1.8, 0, 0, 0); }

// Scans every 0.5 s (a sparse stream: further apart than tracking.search_after) at 1 m a scan, a
// 5 s gap (a restart), then the restart scan and one more `step` metres further on.
FrameResult step_after_restart(double step, FrameResult* restart) {
    const registration::test::Scene scene = registration::test::street_scene();
    registration::test::ScanPattern pattern;
    auto scan = [&](double x, double stamp, int seed) {
        common::PointCloud c =
            registration::test::scan_scene(scene, pattern, street(x), street(x), seed);
        c.stamp = stamp;
        return c;
    };
    Odometry odo(OdometryConfig{}, street(0.0));
    for (int i = 0; i < 4; ++i) {
        const FrameResult r = odo.register_frame(scan(1.0 * i, 0.5 * i, i));
        EXPECT_TRUE(r.registered() || i == 0) << i << ": " << r.message;
    }
    // Truth after the gap: 20 m on (the prediction says 10 m; the restart takes it as it is).
    const double x0 = 3.0 + 20.0;
    *restart = odo.register_frame(scan(x0, 1.5 + 5.0, 10));
    EXPECT_EQ(restart->status, FrameStatus::kRestarted) << restart->message;
    return odo.register_frame(scan(x0 + step, 1.5 + 5.5, 11));
}

class RestartFirstStep : public testing::TestWithParam<double> {};

TEST_P(RestartFirstStep, TheStepAfterARestartIsFoundOrFlagged) {
    const double step = GetParam();
    FrameResult restart;
    const FrameResult r = step_after_restart(step, &restart);
    // The motion from the restart scan: its truth is `step` along x.
    const Isometry3d moved = restart.T_odom_lidar.inverse() * r.T_odom_lidar;
    const double error = (moved.translation() - Eigen::Vector3d(step, 0, 0)).norm();
    const std::string what = "step " + std::to_string(step) + " m: " + to_string(r.status) +
                             ", search " + r.search_used + ", moved " +
                             std::to_string(moved.translation().x()) + " m; " + r.message;
    // A well constrained street: the scan is found, not merely flagged.
    EXPECT_TRUE(r.registered()) << what;
    EXPECT_LT(error, 0.3) << what;
}

// The prediction carries 1 m a scan: a stop, a step the same, and steps 5 and 8 m long.
INSTANTIATE_TEST_SUITE_P(Steps, RestartFirstStep, testing::Values(0.0, 1.0, 5.0, 8.0));

}  // namespace
}  // namespace ltm::odometry
