#include "simulator/core/proprioception.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::sim {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

// Turning on the spot at a steady 1 rad/s, level, 1 m above the ground.
Isometry3d spinning(double t) {
    Isometry3d T = Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(1.0 * t, Vector3d::UnitZ()).matrix();
    T.translation() = Vector3d(3.0, -2.0, 1.0);
    return T;
}

// Driving straight along x at 2 m/s.
Isometry3d driving(double t) {
    Isometry3d T = Isometry3d::Identity();
    T.translation() = Vector3d(2.0 * t, 0.0, 1.0);
    return T;
}

struct Stats {
    Vector3d mean = Vector3d::Zero(), sigma = Vector3d::Zero();
};

template <typename Get>
Stats stats(std::size_t n, Get get) {
    Stats s;
    for (std::size_t i = 0; i < n; ++i) s.mean += get(i);
    s.mean /= double(n);
    for (std::size_t i = 0; i < n; ++i) s.sigma += (get(i) - s.mean).cwiseAbs2();
    s.sigma = (s.sigma / double(n - 1)).cwiseSqrt();
    return s;
}

TEST(Proprioception, GyroAndAccelerometerNoiseHaveTheirConfiguredStatistics) {
    ImuConfig c;
    c.rate = 200.0;
    c.gyro_bias_walk = 0.0;  // a fixed bias: the mean says it
    c.T_lidar_imu.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ()).matrix();
    ImuSimulator imu(c, 7);
    std::vector<ImuSample> out;
    imu.run(spinning, 0.0, 100.0, &out);
    ASSERT_EQ(out.size(), 20000u);
    EXPECT_DOUBLE_EQ(out[1].stamp, 0.005);
    // The IMU turns about z with the LiDAR: 1 rad/s about its own z, plus the bias and noise.
    const Stats g = stats(out.size(), [&](std::size_t i) {
        return Vector3d(out[i].gyro - Vector3d(0, 0, 1.0) - imu.gyro_bias());
    });
    const double gyro_sigma = c.gyro_noise * std::sqrt(c.rate);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(g.mean[k], 0.0, 4.0 * gyro_sigma / std::sqrt(double(out.size()))) << k;
        EXPECT_NEAR(g.sigma[k], gyro_sigma, 0.03 * gyro_sigma) << k;
    }
    // The bias drawn is of the configured size (a few sigma at most) and not zero.
    EXPECT_GT(imu.gyro_bias().norm(), 1e-5);
    EXPECT_LT(imu.gyro_bias().cwiseAbs().maxCoeff(), 4.0 * c.gyro_bias);
    // The IMU is on the turning axis: it feels only gravity, up.
    const Stats a = stats(out.size(), [&](std::size_t i) {
        return Vector3d(out[i].accel - Vector3d(0, 0, 9.81) - imu.accel_bias());
    });
    const double accel_sigma = c.accel_noise * std::sqrt(c.rate);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(a.mean[k], 0.0, 4.0 * accel_sigma / std::sqrt(double(out.size()))) << k;
        EXPECT_NEAR(a.sigma[k], accel_sigma, 0.03 * accel_sigma) << k;
    }
}

TEST(Proprioception, AnOffCentreImuFeelsTheCentripetalAcceleration) {
    ImuConfig c;
    c.accel_noise = 0.0;
    c.accel_bias = 0.0;
    c.T_lidar_imu.translation() = Vector3d(0.5, 0.0, 0.0);  // 0.5 m from the turning axis
    ImuSimulator imu(c, 3);
    std::vector<ImuSample> out;
    imu.run(spinning, 1.0, 2.0, &out);
    for (const ImuSample& s : out) {
        // w^2 r = 0.5 m/s^2 towards the axis (-x in the IMU frame), gravity up.
        EXPECT_NEAR(s.accel.x(), -0.5, 1e-3);
        EXPECT_NEAR(s.accel.y(), 0.0, 1e-3);
        EXPECT_NEAR(s.accel.z(), 9.81, 1e-3);
    }
}

TEST(Proprioception, GyroBiasWalksAtItsConfiguredRate) {
    ImuConfig c;
    c.gyro_bias = 0.0;
    c.gyro_bias_walk = 1e-3;
    // Over T s a random walk spreads by walk * sqrt(T): many IMUs, one spread.
    double sum2 = 0.0;
    const int imus = 200;
    for (int seed = 0; seed < imus; ++seed) {
        ImuSimulator imu(c, std::uint64_t(seed));
        std::vector<ImuSample> out;
        imu.run(driving, 0.0, 4.0, &out);
        sum2 += imu.gyro_bias().squaredNorm() / 3.0;
    }
    const double spread = std::sqrt(sum2 / imus);
    EXPECT_NEAR(spread, c.gyro_bias_walk * 2.0, 0.15 * c.gyro_bias_walk * 2.0);
}

TEST(Proprioception, WheelOdometryHasItsScaleErrorAndSlip) {
    WheelConfig c;
    c.T_lidar_base.translation() = Vector3d(0.0, 0.0, -1.0);
    WheelSimulator wheel(c, 11);
    EXPECT_NE(wheel.scale(), 1.0);
    std::vector<WheelSample> out;
    wheel.run(driving, 0.0, 50.0, &out);
    ASSERT_EQ(out.size(), 2500u);
    // 100 m driven, reported as 100 m times the scale drawn, up to the speed noise.
    const double distance = out.back().T_odom_base.translation().norm();
    const double noise = c.speed_noise * std::sqrt(50.0);  // per sample [m/s], 0.02 s each
    EXPECT_NEAR(distance, 2.0 * 49.98 * wheel.scale(), 4.0 * noise * 0.02 * std::sqrt(2500.0));
    EXPECT_GT(std::abs(distance - 99.96), 1e-3);  // the scale error shows
    const Stats v = stats(out.size(), [&](std::size_t i) {
        return Vector3d(out[i].linear.x() - 2.0 * wheel.scale(), 0.0, 0.0);
    });
    EXPECT_NEAR(v.sigma.x(), noise, 0.05 * noise);
    // Turning on the spot: the turn is off by the turn factor and slips (relative noise).
    WheelSimulator turner(c, 12);
    std::vector<WheelSample> turns;
    turner.run(spinning, 0.0, 100.0, &turns);
    const Stats w = stats(turns.size(), [&](std::size_t i) {
        return Vector3d(turns[i].angular.z() - 1.0 * turner.turn_scale(), 0.0, 0.0);
    });
    const double expected =
        std::sqrt(c.slip * c.slip + c.turn_noise * c.turn_noise * 50.0);  // at 1 rad/s
    EXPECT_NEAR(w.sigma.x(), expected, 0.05 * expected);
    EXPECT_NEAR(w.mean.x(), 0.0, 4.0 * expected / std::sqrt(double(turns.size())));
    // No translation is made up while turning on the spot (the base is on the axis) but the
    // speed noise's random walk.
    EXPECT_LT(turns.back().T_odom_base.translation().norm(),
              4.0 * noise * 0.02 * std::sqrt(double(turns.size())));
}

}  // namespace
}  // namespace ltm::sim
