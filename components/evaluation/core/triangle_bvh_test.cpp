#include "evaluation/core/triangle_bvh.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ltm::eval {
namespace {

const Eigen::Vector3d A(0, 0, 0), B(1, 0, 0), C(0, 1, 0);

TEST(TriangleBvh, ClosestPointHandCases) {
    // Above the face, beyond a vertex, beside an edge, beyond the hypotenuse.
    EXPECT_TRUE(
        closest_point_on_triangle({0.2, 0.2, 3}, A, B, C).isApprox(Eigen::Vector3d(0.2, 0.2, 0)));
    EXPECT_TRUE(closest_point_on_triangle({-1, -1, 0}, A, B, C).isApprox(A));
    EXPECT_TRUE(closest_point_on_triangle({2, -0.5, 0}, A, B, C).isApprox(B));
    EXPECT_TRUE(
        closest_point_on_triangle({0.5, -2, 1}, A, B, C).isApprox(Eigen::Vector3d(0.5, 0, 0)));
    EXPECT_TRUE(
        closest_point_on_triangle({1, 1, 0}, A, B, C).isApprox(Eigen::Vector3d(0.5, 0.5, 0)));
}

TEST(TriangleBvh, DegenerateTrianglesAreSegmentsOrPoints) {
    const Eigen::Vector3d q(0.5, 1, 0);
    // Collinear "triangle" along x from 0 to 1: closest point (0.5, 0, 0).
    EXPECT_TRUE(closest_point_on_triangle(q, A, B, Eigen::Vector3d(0.5, 0, 0))
                    .isApprox(Eigen::Vector3d(0.5, 0, 0)));
    EXPECT_TRUE(closest_point_on_triangle(q, B, B, B).isApprox(B));
}

TEST(TriangleBvh, MatchesBruteForceOnARandomSoup) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-5.0, 5.0), s(-0.5, 0.5);
    std::vector<Eigen::Vector3d> v;
    std::vector<Eigen::Vector3i> t;
    for (int i = 0; i < 1500; ++i) {
        const Eigen::Vector3d c(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) v.push_back(c + Eigen::Vector3d(s(rng), s(rng), s(rng)));
        t.emplace_back(3 * i, 3 * i + 1, 3 * i + 2);
    }
    const TriangleBvh bvh(v, t);
    for (int k = 0; k < 300; ++k) {
        const Eigen::Vector3d q(u(rng) * 1.5, u(rng) * 1.5, u(rng) * 1.5);
        double best = 1e300;
        for (const auto& tri : t)
            best = std::min(
                best, (closest_point_on_triangle(q, v[tri[0]], v[tri[1]], v[tri[2]]) - q).norm());
        EXPECT_NEAR(bvh.distance(q), best, 1e-12);
    }
}

TEST(TriangleBvh, PointsOnlyAndBadIndices) {
    const TriangleBvh points({{0, 0, 0}, {3, 0, 0}}, {});
    EXPECT_DOUBLE_EQ(points.distance({1, 0, 0}), 1.0);
    const TriangleBvh bad({A, B, C}, {{0, 1, 2}, {0, 1, 7}});
    EXPECT_EQ(bad.dropped(), 1u);
    EXPECT_DOUBLE_EQ(bad.distance({0.2, 0.2, 2}), 2.0);
    EXPECT_TRUE(std::isinf(TriangleBvh({}, {}).distance({0, 0, 0})));
}

}  // namespace
}  // namespace ltm::eval
