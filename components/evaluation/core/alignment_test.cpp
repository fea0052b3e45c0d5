#include "evaluation/core/alignment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace ltm::eval {
namespace {

TEST(Alignment, RecoversHandMadeRotationAndTranslation) {
    // est -> ref: 90 deg about z, then +(1, 2, 3).
    const std::vector<Eigen::Vector3d> est = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const std::vector<Eigen::Vector3d> ref = {{1, 2, 3}, {1, 3, 3}, {0, 2, 3}, {1, 2, 4}};
    const Eigen::Isometry3d T = umeyama_se3(est, ref);
    Eigen::Matrix3d R_expected;
    R_expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    EXPECT_TRUE(T.linear().isApprox(R_expected, 1e-12));
    EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1, 2, 3), 1e-12));
}

TEST(Alignment, RecoversRandomRigidTransform) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    std::vector<Eigen::Vector3d> est, ref;
    Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity();
    T_true.linear() = Eigen::AngleAxisd(2.5, Eigen::Vector3d(1, -2, 0.5).normalized()).matrix();
    T_true.translation() = Eigen::Vector3d(3, -4, 5);
    for (int i = 0; i < 50; ++i) {
        est.emplace_back(u(rng), u(rng), u(rng));
        ref.push_back(T_true * est.back());
    }
    const Eigen::Isometry3d T = umeyama_se3(est, ref);
    EXPECT_TRUE(T.matrix().isApprox(T_true.matrix(), 1e-9));
}

TEST(Alignment, Sim3RecoversScaleRotationAndTranslation) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-50.0, 50.0);
    std::vector<Eigen::Vector3d> est, ref;
    Eigen::Isometry3d T_true = Eigen::Isometry3d::Identity();
    T_true.linear() = Eigen::AngleAxisd(0.8, Eigen::Vector3d(0.1, 0.2, 1).normalized()).matrix();
    T_true.translation() = Eigen::Vector3d(-7, 2, 0.5);
    const double s_true = 1.0013;  // a map 0.13 % short of the truth
    for (int i = 0; i < 40; ++i) {
        est.emplace_back(u(rng), u(rng), 0.1 * u(rng));
        ref.push_back(T_true * (s_true * est.back()));
    }
    double s = 0.0;
    const Eigen::Isometry3d T = umeyama_sim3(est, ref, &s);
    EXPECT_NEAR(s, s_true, 1e-12);
    EXPECT_TRUE(T.matrix().isApprox(T_true.matrix(), 1e-9));
    // The rigid fit cannot take the scale: it leaves errors of centimetres at 50 m.
    const Eigen::Isometry3d R = umeyama_se3(est, ref);
    double worst = 0.0;
    for (std::size_t i = 0; i < est.size(); ++i)
        worst = std::max(worst, (R * est[i] - ref[i]).norm());
    EXPECT_GT(worst, 0.02);
    // One point: no scale to fit.
    double one = 0.0;
    umeyama_sim3({est[0]}, {ref[0]}, &one);
    EXPECT_EQ(one, 1.0);
}

TEST(Alignment, NeverReturnsAReflection) {
    // ref is est mirrored in the plane x = 0: the best rotation must still have det +1.
    const std::vector<Eigen::Vector3d> est = {{1, 0, 0}, {2, 1, 0}, {3, 0, 1}, {1, 2, 2}};
    std::vector<Eigen::Vector3d> ref;
    for (const auto& p : est) ref.emplace_back(-p.x(), p.y(), p.z());
    const Eigen::Isometry3d T = umeyama_se3(est, ref);
    EXPECT_NEAR(T.linear().determinant(), 1.0, 1e-12);
}

TEST(Alignment, OnePairIsATranslationAndNoPairIsIdentity) {
    const Eigen::Isometry3d T = umeyama_se3({{1, 1, 1}}, {{2, 3, 4}});
    EXPECT_TRUE(T.linear().isApprox(Eigen::Matrix3d::Identity()));
    EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
    EXPECT_TRUE(umeyama_se3({}, {}).matrix().isApprox(Eigen::Matrix4d::Identity()));
}

}  // namespace
}  // namespace ltm::eval
