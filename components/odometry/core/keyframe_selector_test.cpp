#include "odometry/core/keyframe_selector.hpp"

#include <gtest/gtest.h>

#include "registration/core/se3.hpp"

namespace ltm::odometry {
namespace {

TEST(KeyframeSelector, FirstPoseThenEveryDistanceOrAngle) {
    KeyframeConfig config;
    config.distance = 1.0;
    config.angle = 10.0;
    KeyframeSelector k(config);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    EXPECT_TRUE(k.check(T));
    int count = 0;
    for (int i = 1; i <= 100; ++i) {  // 0.25 m a step: every fourth step
        T.translation().x() = 0.25 * i;
        count += k.check(T);
    }
    EXPECT_EQ(count, 25);
    // Turning on the spot, 2.6 deg a step: every fourth step.
    count = 0;
    for (int i = 1; i <= 36; ++i) {
        T.linear() = registration::so3_exp(Eigen::Vector3d(0, 0, 2.6 * i * M_PI / 180.0));
        count += k.check(T);
    }
    EXPECT_EQ(count, 9);
    k.reset();
    EXPECT_TRUE(k.check(T));
}

}  // namespace
}  // namespace ltm::odometry
