#include "evaluation/core/point_grid.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ltm::eval {
namespace {

TEST(PointGrid, MatchesBruteForce) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-2.0f, 2.0f);
    std::vector<Eigen::Vector3f> points;
    for (int i = 0; i < 2000; ++i) points.emplace_back(u(rng), u(rng), u(rng));
    const double r = 0.15;
    const PointGrid grid(points, r);
    for (int k = 0; k < 2000; ++k) {
        const Eigen::Vector3f q(u(rng), u(rng), u(rng));
        double best = -1.0;
        for (const auto& p : points) {
            const double d = (p - q).cast<double>().norm();
            if (d <= r && (best < 0 || d < best)) best = d;
        }
        const double got = grid.nearest_within(q);
        if (best < 0) {
            EXPECT_LT(got, 0.0);
        } else {
            EXPECT_NEAR(got, best, 1e-6);
        }
    }
}

TEST(PointGrid, RadiusIsInclusiveAndNegativeCoordinatesWork) {
    const PointGrid grid({{-10.0f, -10.0f, -10.0f}}, 0.5);
    EXPECT_TRUE(grid.has_neighbour({-10.5f, -10.0f, -10.0f}));
    EXPECT_FALSE(grid.has_neighbour({-10.6f, -10.0f, -10.0f}));
    EXPECT_FALSE(PointGrid({}, 0.5).has_neighbour({0, 0, 0}));
}

}  // namespace
}  // namespace ltm::eval
