// De-skewing inside the tracking loop: the velocity that de-skews a scan comes from the poses the
// earlier de-skewed scans gave. Registered in the frame at the stamp, a scan de-skewed with a
// velocity error e is off by (t - t_stamp) * e, half a sweep of it on average, which shifts its
// pose; the next velocity then carries that shift with the opposite sign: a frame-to-frame
// oscillation that never dies out (worse than not de-skewing at all on fast simulated sweeps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "odometry/core/odometry.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Isometry3d;

// 10 m/s along the synthetic street with some weaving: each 0.1 s sweep is smeared by 1 m.
Isometry3d drive(double t) {
    return registration::test::make_pose(10.0 * t, 0.4 * std::sin(2.0 * t), 1.8, 0.0, 0.0,
                                         6.0 * std::sin(1.25 * t));
}

// The largest error of the consecutive-frame motion [m] from frame `from` on.
double worst_relative_error(const registration::test::Scene& scene, bool deskew, int from,
                            int frames) {
    OdometryConfig config;
    config.preprocess.deskew = deskew;
    Odometry odo(config, drive(0.0));
    registration::test::ScanPattern pattern;
    Isometry3d last = drive(0.0);
    double worst = 0.0;
    for (int i = 0; i < frames; ++i) {
        const double t = 0.1 * i;
        common::PointCloud c =
            registration::test::scan_scene(scene, pattern, drive(t), drive(t + 0.1), 300 + i, true);
        c.stamp = t;
        const FrameResult r = odo.register_frame(c);
        EXPECT_TRUE(r.pose_valid()) << i << ": " << r.message;
        if (i >= from) {
            const Isometry3d truth = drive(t - 0.1).inverse() * drive(t);
            const Isometry3d d = truth.inverse() * (last.inverse() * r.T_odom_lidar);
            worst = std::max(worst, d.translation().norm());
        }
        last = r.T_odom_lidar;
    }
    return worst;
}

TEST(OdometryDeskew, VelocityErrorsDieOutInsteadOfOscillating) {
    const registration::test::Scene scene = registration::test::street_scene();
    // The first scans enter un-de-skewed (no motion known yet); after that the error must settle.
    const double on = worst_relative_error(scene, true, 6, 16);
    const double off = worst_relative_error(scene, false, 6, 16);
    EXPECT_LT(on, 0.02);
    EXPECT_LT(on, 0.5 * off);
}

}  // namespace
}  // namespace ltm::odometry
