#include "odometry/core/motion_prior.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::odometry {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

constexpr double kRate = 200.0;  // [Hz] IMU samples

// An IMU turned 90 deg about z on the LiDAR (its x is the LiDAR's y).
MotionPriorConfig turned_imu() {
    MotionPriorConfig c;
    c.T_lidar_imu.linear() = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ()).matrix();
    c.T_lidar_imu.translation() = Vector3d(-0.05, 0.0, -0.08);
    return c;
}

// Feeds a constant body rate `w_imu` (IMU frame) plus `bias` from t0 to t1.
void feed_gyro(MotionPrior& p, double t0, double t1, const Vector3d& w_imu, const Vector3d& bias) {
    for (int k = int(std::ceil(t0 * kRate)); k / kRate <= t1; ++k)
        p.add_imu(k / kRate, w_imu + bias);
}

double angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
    return Eigen::AngleAxisd(a.transpose() * b).angle();
}

TEST(MotionPrior, ConstantRateIsIntegratedInTheLidarFrame) {
    const MotionPriorConfig c = turned_imu();
    MotionPrior p(c);
    const Vector3d w_imu(0.3, -0.2, 1.5);  // [rad/s]
    feed_gyro(p, 0.0, 1.0, w_imu, Vector3d::Zero());
    // Between arbitrary stamps, not on the sample grid.
    const std::optional<PriorMotion> m = p.between(0.1234, 0.3734);
    ASSERT_TRUE(m.has_value());
    EXPECT_TRUE(m->has_rotation);
    EXPECT_FALSE(m->has_translation);  // no wheels: the translation is not measured
    const Eigen::Matrix3d L = c.T_lidar_imu.linear();
    const Eigen::Matrix3d truth = L * registration::so3_exp(w_imu * 0.25) * L.transpose();
    EXPECT_LT(angle_between(m->T_lidar0_lidar1.linear(), truth), 1e-9);
    EXPECT_TRUE(m->rate.isApprox(L * w_imu, 1e-9));
    // Variance: white noise over 0.25 s and the unknown bias for 0.25 s.
    const double var = c.gyro_noise * c.gyro_noise * 0.25 + std::pow(c.gyro_bias * 0.25, 2);
    EXPECT_NEAR(m->covariance(3, 3), var, 1e-12);
    EXPECT_GT(m->covariance(0, 0), 1e3);
    // Outside the samples (beyond max_gap) there is nothing to say.
    EXPECT_FALSE(p.between(0.5, 1.5).has_value());
    EXPECT_FALSE(p.between(0.3, 0.2).has_value());
}

TEST(MotionPrior, NoPriorAcrossAGapInTheSamples) {
    MotionPrior p(turned_imu());
    feed_gyro(p, 0.0, 1.0, Vector3d(0, 0, 1), Vector3d::Zero());
    feed_gyro(p, 2.0, 3.0, Vector3d(0, 0, 1), Vector3d::Zero());
    EXPECT_TRUE(p.between(0.2, 0.9).has_value());
    EXPECT_FALSE(p.between(0.9, 2.1).has_value());
    EXPECT_TRUE(p.between(2.1, 2.9).has_value());
}

TEST(MotionPrior, GyroBiasIsLearntFromTheFits) {
    MotionPriorConfig c = turned_imu();
    MotionPrior p(c);
    const Vector3d w_imu(0.0, 0.0, 0.8), bias(0.004, -0.003, 0.006);
    const Eigen::Matrix3d L = c.T_lidar_imu.linear();
    // A steady turn for 40 s; a registered fit at every scan (10 Hz) with the true rotation.
    double t = 0.0;
    feed_gyro(p, 0.0, 0.2, w_imu, bias);
    const std::optional<PriorMotion> before = p.between(0.0, 0.1);
    ASSERT_TRUE(before.has_value());
    for (int i = 1; i <= 400; ++i) {
        feed_gyro(p, t + 0.2 + 1e-9, t + 0.3, w_imu, bias);
        t = 0.1 * i;
        const Eigen::Matrix3d R_odom_lidar = L * registration::so3_exp(w_imu * t) * L.transpose();
        p.observe(t, R_odom_lidar, true);
    }
    EXPECT_LT((p.gyro_bias() - bias).norm(), 2e-4) << p.gyro_bias().transpose();
    // The prior over a scan is then right to the remaining bias.
    const std::optional<PriorMotion> after = p.between(t - 0.1, t);
    ASSERT_TRUE(after.has_value());
    const Eigen::Matrix3d truth = L * registration::so3_exp(w_imu * 0.1) * L.transpose();
    EXPECT_LT(angle_between(after->T_lidar0_lidar1.linear(), truth), 2e-5);
    EXPECT_GT(angle_between(before->T_lidar0_lidar1.linear(), truth), 5e-4);
    // Scans that were not registered learn nothing.
    MotionPrior q(c);
    feed_gyro(q, 0.0, 10.0, w_imu, bias);
    for (int i = 1; i <= 90; ++i) q.observe(0.1 * i, Eigen::Matrix3d::Identity(), false);
    EXPECT_TRUE(q.gyro_bias().isZero());
}

TEST(MotionPrior, WheelOdometryGivesTheLidarsTranslation) {
    MotionPriorConfig c;
    c.T_lidar_base.translation() = Vector3d(0.0, 0.0, -0.6);  // base 0.6 m below the LiDAR
    MotionPrior p(c);
    // 1 m/s forward while turning at 0.5 rad/s, 50 Hz.
    for (int k = 0; k <= 100; ++k) {
        const double t = k / 50.0;
        Isometry3d T = Isometry3d::Identity();
        T.linear() = Eigen::AngleAxisd(0.5 * t, Vector3d::UnitZ()).matrix();
        T.translation() = Vector3d(std::sin(0.5 * t) / 0.5, (1 - std::cos(0.5 * t)) / 0.5, 0.0);
        p.add_wheel(t, T);
    }
    const std::optional<PriorMotion> m = p.between(0.5, 0.7);
    ASSERT_TRUE(m.has_value());
    EXPECT_TRUE(m->has_translation);
    EXPECT_TRUE(m->has_rotation);
    // The base is below the LiDAR with the same axes: the LiDAR moves as the base does.
    EXPECT_NEAR(m->T_lidar0_lidar1.translation().norm(), 0.2, 2e-3);
    EXPECT_NEAR(Eigen::AngleAxisd(m->T_lidar0_lidar1.linear()).angle(), 0.1, 1e-3);
    EXPECT_GT(m->covariance(0, 0), 1e-4);
    EXPECT_LT(m->covariance(0, 0), 1e-3);
}

TEST(MotionPrior, FillsOnlyTheUnobservedDirections) {
    MotionPriorConfig c;
    MotionPrior p(c);
    for (int k = 0; k <= 50; ++k) {  // straight on at 10 m/s
        Isometry3d T = Isometry3d::Identity();
        T.translation() = Vector3d(10.0 * k / 50.0, 0.0, 0.0);
        p.add_wheel(k / 50.0, T);
    }
    const Isometry3d T0 = Isometry3d::Identity();
    Isometry3d fit = Isometry3d::Identity();  // slid back along the road: 0.2 m instead of 1 m
    fit.translation() = Vector3d(0.2, 0.05, 0.0);
    registration::Vector6d along_x = registration::Vector6d::Zero();
    along_x(0) = 1.0;
    const Isometry3d filled = p.fill_unobserved(T0, 0.2, 0.3, fit, {along_x}, 3.0);
    EXPECT_NEAR(filled.translation().x(), 1.0, 1e-6);   // the wheels' distance along the road
    EXPECT_NEAR(filled.translation().y(), 0.05, 1e-9);  // the fit where it saw
    // Without a degenerate direction the fit stands.
    EXPECT_TRUE(p.fill_unobserved(T0, 0.2, 0.3, fit, {}, 3.0).isApprox(fit));
    // The gate: 0.8 m off the wheels is refused, 0.1 m is not.
    EXPECT_FALSE(p.disagreement(T0, 0.2, 0.3, fit).empty());
    Isometry3d close = Isometry3d::Identity();
    close.translation() = Vector3d(0.9, 0.0, 0.0);
    EXPECT_EQ(p.disagreement(T0, 0.2, 0.3, close), "");
}

TEST(MotionPrior, RefusesAFitTurnedOffTheGyro) {
    MotionPrior p(turned_imu());
    feed_gyro(p, 0.0, 1.0, Vector3d(0, 0, M_PI / 2), Vector3d::Zero());  // 9 deg a scan
    const Isometry3d T0 = Isometry3d::Identity();
    Isometry3d fit = Isometry3d::Identity();
    fit.linear() = Eigen::AngleAxisd(9.2 * M_PI / 180.0, Vector3d::UnitZ()).matrix();
    EXPECT_EQ(p.disagreement(T0, 0.3, 0.4, fit), "");
    fit.linear() = Eigen::AngleAxisd(3.0 * M_PI / 180.0, Vector3d::UnitZ()).matrix();
    EXPECT_NE(p.disagreement(T0, 0.3, 0.4, fit).find("deg off the motion prior"),
              std::string::npos);
    // The prediction turns as the gyro did, from any constant-velocity guess.
    const Isometry3d predicted = p.predict(T0, 0.3, 0.4, Isometry3d::Identity());
    EXPECT_NEAR(Eigen::AngleAxisd(predicted.linear()).angle(), M_PI / 20, 1e-9);
}

TEST(MotionPrior, BadConfigsAreRefusedWithTheirKey) {
    MotionPriorConfig c;
    c.gyro_noise = -1.0;
    EXPECT_EQ(validate(c)->key, "gyro_noise");
    c = MotionPriorConfig{};
    c.T_lidar_imu.linear() *= 2.0;
    EXPECT_EQ(validate(c)->key, "imu_extrinsic");
    c = MotionPriorConfig{};
    c.keep_seconds = 0.1;
    EXPECT_THROW(MotionPrior{c}, common::ConfigError);
    EXPECT_FALSE(validate(MotionPriorConfig{}).has_value());
}

}  // namespace
}  // namespace ltm::odometry
