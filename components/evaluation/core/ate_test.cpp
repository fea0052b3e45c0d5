#include "evaluation/core/ate.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

common::PoseList at_positions(const std::vector<Eigen::Vector3d>& ps) {
    common::PoseList out;
    for (const auto& p : ps) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = p;
        out.push_back(T);
    }
    return out;
}

TEST(Ate, HandComputedWithoutAlignment) {
    // Errors 0, 3, 4: RMSE sqrt(25/3), mean 7/3, median 3, max 4.
    const auto ref = at_positions({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}});
    const auto est = at_positions({{0, 0, 0}, {4, 0, 0}, {2, 4, 0}});
    const AteResult r = compute_ate(est, ref, false);
    EXPECT_EQ(r.n, 3u);
    EXPECT_NEAR(r.rmse, std::sqrt(25.0 / 3.0), 1e-12);
    EXPECT_NEAR(r.mean, 7.0 / 3.0, 1e-12);
    EXPECT_NEAR(r.median, 3.0, 1e-12);
    EXPECT_NEAR(r.max, 4.0, 1e-12);
}

TEST(Ate, AlignmentRemovesARigidMotionButNotTheShapeError) {
    // Reference: a cross in the plane z = 0. Estimate: the x arm lifted 0.1 m, the y arm lowered
    // 0.1 m. No rigid motion reduces that (mean offset 0, cross-covariance diag(2, 2, 0)/4), so
    // every aligned error is 0.1 m, whatever rigid motion is applied to the estimate first.
    const auto ref = at_positions({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}});
    auto est = at_positions({{1, 0, 0.1}, {-1, 0, 0.1}, {0, 1, -0.1}, {0, -1, -0.1}});
    Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
    M.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d(0.3, 0.4, 0.5).normalized()).matrix();
    M.translation() = Eigen::Vector3d(10, -20, 3);
    est = transform_poses(M, est);

    const AteDetail d = compute_ate_detail(est, ref, true);
    EXPECT_NEAR(d.stats.rmse, 0.1, 1e-9);
    EXPECT_NEAR(d.stats.max, 0.1, 1e-9);
    EXPECT_NEAR(d.stats.median, 0.1, 1e-9);
    EXPECT_TRUE((d.T_ref_est * M).matrix().isApprox(Eigen::Matrix4d::Identity(), 1e-9));
    ASSERT_EQ(d.errors.size(), 4u);

    const AteResult unaligned = compute_ate(est, ref, false);
    EXPECT_GT(unaligned.rmse, 5.0);
}

TEST(Ate, UsesTheCommonPrefixOfDifferentLengths) {
    const auto ref = at_positions({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
    const auto est = at_positions({{0, 0, 0}, {1, 0, 0}});
    EXPECT_EQ(compute_ate(est, ref).n, 2u);
    EXPECT_EQ(compute_ate({}, ref).n, 0u);
}

}  // namespace
}  // namespace ltm::eval
