#include "odometry/core/local_map_set.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ltm::odometry {
namespace {

// A flat patch of ground around the sensor, in the sensor frame.
std::vector<Eigen::Vector3f> ground(std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-30.0f, 30.0f);
    std::vector<Eigen::Vector3f> pts;
    for (int i = 0; i < 20000; ++i) pts.emplace_back(u(rng), u(rng), -1.8f);
    return pts;
}

Eigen::Isometry3d at(double x) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().x() = x;
    return T;
}

TEST(LocalMapSet, StartsSeedsAndFinishesMaps) {
    OdometryConfig config;
    config.local_map.half_extent = 20.0;
    config.local_map.switch_distance = 10.0;
    config.local_map.max_active_maps = 2;
    LocalMapSet set(config);
    EXPECT_TRUE(set.empty());
    EXPECT_TRUE(set.integrate(ground(1), at(0.0), 0.0));  // the first map
    EXPECT_EQ(set.current().id(), 0u);
    EXPECT_FALSE(set.integrate(ground(2), at(9.0), 1.0));  // still inside the switch box
    const std::size_t before = set.current().voxels().size();
    ASSERT_GT(before, 0u);

    EXPECT_TRUE(set.integrate(ground(3), at(11.0), 2.0));  // left it: map 1, seeded from map 0
    ASSERT_EQ(set.active().size(), 2u);
    EXPECT_EQ(set.current().id(), 1u);
    EXPECT_TRUE(set.current().T_odom_anchor().isApprox(at(11.0)));
    EXPECT_GT(set.current().voxels().records()[0].observations, 1u);  // copied history
    // The scan updated both maps (their boxes overlap).
    EXPECT_EQ(set.active().front().scans_integrated(), 3u);
    EXPECT_EQ(set.current().scans_integrated(), 1u);
    EXPECT_EQ(set.finished_pending(), 0u);

    EXPECT_TRUE(set.integrate(ground(4), at(22.0), 3.0));  // map 2: map 0 is finished
    EXPECT_EQ(set.active().size(), 2u);
    std::vector<LocalMap> finished = set.take_finished();
    ASSERT_EQ(finished.size(), 1u);
    EXPECT_EQ(finished[0].id(), 0u);
    EXPECT_TRUE(set.take_finished().empty());  // handed out once

    set.finish_all();
    EXPECT_TRUE(set.empty());
    finished = set.take_finished();
    ASSERT_EQ(finished.size(), 2u);
    EXPECT_EQ(finished[0].id(), 1u);
    EXPECT_EQ(finished[1].id(), 2u);
}

}  // namespace
}  // namespace ltm::odometry
