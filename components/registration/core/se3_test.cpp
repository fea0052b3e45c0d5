#include "registration/core/se3.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ltm::registration {
namespace {

Vector6d random_twist(std::mt19937& rng, double scale) {
    std::normal_distribution<double> n(0.0, scale);
    Vector6d xi;
    for (int i = 0; i < 6; ++i) xi[i] = n(rng);
    return xi;
}

TEST(Se3, ExpAndLogAreInverse) {
    std::mt19937 rng(1);
    for (const double scale : {1e-9, 1e-4, 0.1, 1.0}) {
        for (int k = 0; k < 50; ++k) {
            const Vector6d xi = random_twist(rng, scale);
            if (xi.tail<3>().norm() >= 3.0) continue;  // log returns angles in [0, pi]
            EXPECT_LT((se3_log(se3_exp(xi)) - xi).norm(), 1e-9 + 1e-9 * xi.norm()) << scale;
        }
    }
}

TEST(Se3, ExpMatchesTheMatrixExponential) {
    // exp of the 4x4 twist matrix by a long Taylor series.
    std::mt19937 rng(2);
    const Vector6d xi = random_twist(rng, 0.7);
    Eigen::Matrix4d X = Eigen::Matrix4d::Zero();
    X.block<3, 3>(0, 0) << 0, -xi[5], xi[4], xi[5], 0, -xi[3], -xi[4], xi[3], 0;
    X.block<3, 1>(0, 3) = xi.head<3>();
    Eigen::Matrix4d term = Eigen::Matrix4d::Identity(), sum = Eigen::Matrix4d::Identity();
    for (int k = 1; k < 40; ++k) {
        term = term * X / double(k);
        sum += term;
    }
    EXPECT_LT((se3_exp(xi).matrix() - sum).norm(), 1e-12);
}

TEST(Se3, ScaleMotionInterpolatesTheScrew) {
    std::mt19937 rng(3);
    const Eigen::Isometry3d T = se3_exp(random_twist(rng, 0.3));
    const Eigen::Isometry3d half = scale_motion(T, 0.5);
    EXPECT_TRUE((half * half).isApprox(T, 1e-12));
    EXPECT_TRUE(scale_motion(T, 1.0).isApprox(T));
    EXPECT_TRUE(scale_motion(T, 0.0).isApprox(Eigen::Isometry3d::Identity()));
    EXPECT_NEAR(rotation_angle(scale_motion(T, 2.0)), 2.0 * rotation_angle(T), 1e-12);
}

TEST(Se3, RotationAngleIsAccurateForTinyAngles) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = so3_exp(Eigen::Vector3d(1e-9, 0, 0));
    EXPECT_NEAR(rotation_angle(T), 1e-9, 1e-15);
}

}  // namespace
}  // namespace ltm::registration
