#include "maintenance/core/point_sums.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

namespace ltm::maintenance {
namespace {

TEST(PointSums, CentreAndNormalAsFloatSumsGiveThem) {
    std::mt19937 rng(11);
    const float size = 0.25f;
    std::uniform_real_distribution<float> u(-0.12f, 0.12f);
    std::normal_distribution<float> noise(0.0f, 0.01f);
    for (int trial = 0; trial < 50; ++trial) {
        const Eigen::Vector3f n = Eigen::Vector3f(u(rng), u(rng), 0.2f).normalized();
        PointSums fixed;
        registration::VoxelSums exact;
        const int points = 3 + trial;
        for (int i = 0; i < points; ++i) {  // a noisy plane through the cell
            Eigen::Vector3f q(u(rng), u(rng), 0.0f);
            q.z() = -(n.x() * q.x() + n.y() * q.y()) / n.z() + noise(rng);
            q = q.cwiseMax(-0.125f).cwiseMin(0.125f);
            fixed.add(q, size);
            if (exact.weight < float(PointSums::kMaxPoints)) exact.add(q);
        }
        const registration::VoxelSums s = fixed.sums(size);
        ASSERT_EQ(s.weight, exact.weight);
        EXPECT_LT((s.mean() - exact.mean()).norm(), 1e-3f) << trial;
        // The normal within a degree and the spread across the plane (what the plane and ground
        // tests read) within one unit of the products (32 (1 mm)^2 = 3.1e-5 m^2).
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> a(s.covariance()), b(exact.covariance());
        const double cos_angle = std::abs(a.eigenvectors().col(0).dot(b.eigenvectors().col(0)));
        EXPECT_GT(cos_angle, std::cos(1.0 / 57.2958)) << trial;
        const double unit = 0.25 / PointSums::kUnitsPerVoxel;
        EXPECT_LT(std::abs(a.eigenvalues()(0) - b.eigenvalues()(0)),
                  PointSums::kSquareUnit * unit * unit)
            << trial;
    }
}

TEST(PointSums, StopsAtItsCapacityAndSkipsBadPoints) {
    PointSums p;
    for (int i = 0; i < 100; ++i) p.add(Eigen::Vector3f(0.125f, -0.125f, 0.125f), 0.25f);
    EXPECT_EQ(p.count, PointSums::kMaxPoints);
    // The extreme corner 64 times fits, a unit inside the cell (127 of 128 units).
    const float edge = 0.25f * 127.0f / 256.0f;
    EXPECT_NEAR(p.sums(0.25f).mean().x(), edge, 1e-6f);
    EXPECT_NEAR(p.sums(0.25f).mean().y(), -edge, 1e-6f);
    EXPECT_NEAR(p.sums(0.25f).sum_sq(0) / 64.0f, edge * edge, 1e-5f);
    PointSums q;
    q.add(Eigen::Vector3f(NAN, 0.0f, 0.0f), 0.25f);
    EXPECT_EQ(q.count, 0);
}

}  // namespace
}  // namespace ltm::maintenance
