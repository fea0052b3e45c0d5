#include "registration/core/ransac_alignment.hpp"

#include <gtest/gtest.h>

#include <random>

#include "registration/core/se3.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::registration {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

struct Data {
    std::vector<Vector3d> source, target;
    std::vector<bool> good;
};

// n correspondences over a 60 m area: a fraction `outliers` point somewhere else at random.
Data make_data(const Isometry3d& T, int n, double outliers, double noise, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-30.0, 30.0), h(-2.0, 5.0), pick(0.0, 1.0);
    std::normal_distribution<double> g(0.0, noise);
    Data d;
    for (int i = 0; i < n; ++i) {
        const Vector3d p(u(rng), u(rng), h(rng));
        d.source.push_back(p);
        const bool good = pick(rng) >= outliers;
        d.good.push_back(good);
        d.target.push_back(good ? Vector3d(T * p + Vector3d(g(rng), g(rng), g(rng)))
                                : Vector3d(u(rng), u(rng), h(rng)));
    }
    return d;
}

TEST(RansacAlignment, FindsTheMotionWithMostCorrespondencesWrong) {
    const Isometry3d T = test::make_pose(12.0, -7.0, 0.4, 2.0, -1.0, 135.0);
    for (const double outliers : {0.0, 0.5, 0.8}) {
        const Data d = make_data(T, 200, outliers, 0.05, 3);
        const auto r = ransac_align(d.source, d.target);
        ASSERT_TRUE(r.has_value()) << outliers;
        const Isometry3d e = T.inverse() * r->T_target_source;
        EXPECT_LT(e.translation().norm(), 0.05) << outliers;
        EXPECT_LT(rotation_angle(e) * 180.0 / M_PI, 0.2) << outliers;
        std::size_t wrong = 0;
        for (const std::size_t i : r->inliers) wrong += !d.good[i];
        EXPECT_LE(wrong, 2u) << outliers;  // a random target can fall near by chance
        EXPECT_LT(r->inlier_rms, 0.15);
    }
}

TEST(RansacAlignment, NoAnswerWhenNothingAgrees) {
    const Data d = make_data(Isometry3d::Identity(), 200, 1.0, 0.0, 5);
    EXPECT_FALSE(ransac_align(d.source, d.target).has_value());
    // Too few correspondences, or mismatched lists.
    EXPECT_FALSE(
        ransac_align({Vector3d::Zero(), Vector3d::UnitX()}, {Vector3d::Zero(), Vector3d::UnitX()})
            .has_value());
    EXPECT_FALSE(ransac_align({Vector3d::Zero()}, {}).has_value());
}

TEST(RansacAlignment, DeterministicForASeed) {
    const Isometry3d T = test::make_pose(1.0, 2.0, 0.0, 0.0, 0.0, 30.0);
    const Data d = make_data(T, 100, 0.6, 0.05, 8);
    const auto a = ransac_align(d.source, d.target);
    const auto b = ransac_align(d.source, d.target);
    ASSERT_TRUE(a && b);
    EXPECT_TRUE(a->T_target_source.isApprox(b->T_target_source));
    EXPECT_EQ(a->inliers, b->inliers);
}

TEST(RansacAlignment, ConfigRulesNameTheKey) {
    RansacAlignmentConfig c;
    c.min_inliers = 2;
    const auto p = validate(c);
    ASSERT_TRUE(p.has_value());
    EXPECT_EQ(p->key, "min_inliers");
    EXPECT_FALSE(validate(RansacAlignmentConfig{}).has_value());
}

}  // namespace
}  // namespace ltm::registration
