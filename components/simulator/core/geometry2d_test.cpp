#include "simulator/core/geometry2d.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "simulator/core/free_space.hpp"
#include "simulator/core/random.hpp"

namespace ltm::sim {
namespace {

TEST(Geometry2d, RoundedCornerStaysWithinItsRadius) {
    const Points2 square = {{0, 0}, {20, 0}, {20, 20}};
    std::vector<std::size_t> index;
    const Points2 r = round_corners(square, 4.0, 0.25, &index);
    EXPECT_NEAR((r.front() - square.front()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r.back() - square.back()).norm(), 0.0, 1e-12);
    ASSERT_EQ(index.size(), 3u);
    EXPECT_EQ(index[0], 0u);
    EXPECT_EQ(index[2], r.size() - 1);
    // Points of the arc are 4 m from the centre (16, 4); the corner's stand-in is on the arc.
    const Eigen::Vector2d centre(16, 4);
    int on_arc = 0;
    for (const auto& p : r) {
        if (p.x() > 16 && p.y() < 4) {
            EXPECT_NEAR((p - centre).norm(), 4.0, 1e-9);
            ++on_arc;
        }
    }
    EXPECT_GT(on_arc, 10);
    EXPECT_NEAR((r[index[1]] - centre).norm(), 4.0, 1e-9);
    // Arc length: two 16 m legs and a quarter circle.
    EXPECT_NEAR(Polyline(r).length(), 32 + M_PI * 2, 0.01);
}

TEST(Geometry2d, PolylineInterpolatesByArcLength) {
    const Polyline line({{0, 0}, {10, 0}, {10, 5}});
    EXPECT_DOUBLE_EQ(line.length(), 15.0);
    EXPECT_TRUE(line.point_at(12.0).isApprox(Eigen::Vector2d(10, 2)));
    EXPECT_TRUE(line.point_at(-3).isApprox(Eigen::Vector2d(0, 0)));
    EXPECT_TRUE(line.point_at(99).isApprox(Eigen::Vector2d(10, 5)));
    EXPECT_TRUE(line.tangent_at(3).isApprox(Eigen::Vector2d(1, 0)));
    EXPECT_NEAR(line.project({10.5, 4}), 14.0, 1e-12);
}

TEST(Geometry2d, OffsetKeepsItsDistance) {
    const Points2 line = {{0, 0}, {10, 0}, {10, 10}};
    const Points2 left = offset_polyline(line, 2.0);
    ASSERT_EQ(left.size(), 3u);
    EXPECT_TRUE(left[0].isApprox(Eigen::Vector2d(0, 2)));
    EXPECT_TRUE(left[1].isApprox(Eigen::Vector2d(8, 2)));  // mitred corner (inside of the turn)
    EXPECT_TRUE(left[2].isApprox(Eigen::Vector2d(8, 10)));
}

TEST(Geometry2d, RectanglesAgreeWithSampling) {
    Rng rng(5);
    for (int k = 0; k < 300; ++k) {
        OrientedRect a{{rng.uniform(-5, 5), rng.uniform(-5, 5)},
                       {rng.uniform(0.2, 3), rng.uniform(0.2, 3)},
                       rng.uniform(0, M_PI)};
        OrientedRect b{{rng.uniform(-5, 5), rng.uniform(-5, 5)},
                       {rng.uniform(0.2, 3), rng.uniform(0.2, 3)},
                       rng.uniform(0, M_PI)};
        // Brute force: a grid of points of a inside b?
        bool sampled = false;
        for (int i = 0; i <= 40 && !sampled; ++i) {
            for (int j = 0; j <= 40 && !sampled; ++j) {
                const Eigen::Vector2d p = a.center + (i / 20.0 - 1) * a.half.x() * a.axis_x() +
                                          (j / 20.0 - 1) * a.half.y() * a.axis_y();
                sampled = b.contains(p);
            }
        }
        if (sampled) {
            EXPECT_TRUE(rects_overlap(a, b, 0.0));
        }
        // Segment distance against sampling the segment and the rectangle's outline.
        const Eigen::Vector2d s0(rng.uniform(-8, 8), rng.uniform(-8, 8)),
            s1(rng.uniform(-8, 8), rng.uniform(-8, 8));
        double best = 1e9;
        for (int i = 0; i <= 400; ++i) {
            const Eigen::Vector2d p = s0 + (s1 - s0) * (i / 400.0);
            if (a.contains(p)) best = 0;
            for (int c = 0; c < 4; ++c)
                best =
                    std::min(best, point_segment_distance(p, a.corner(c), a.corner((c + 1) % 4)));
        }
        EXPECT_NEAR(segment_rect_distance(s0, s1, a), best, 0.05);
    }
}

TEST(FreeSpace, KeepsCorridorsAndFootprintsClear) {
    FreeSpace space(5.0);
    space.add_corridor({{0, 0}, {100, 0}}, 3.0, true);
    space.add_corridor({{0, 20}, {100, 20}}, 1.0, false);
    const OrientedRect on_road{{50, 2}, {1, 1}, 0.0};
    const OrientedRect beside{{50, 6}, {1, 1}, 0.0};
    EXPECT_FALSE(space.is_free(on_road, 0.0, 0.0));
    EXPECT_TRUE(space.is_free(beside, 1.5, 0.0));   // 5 m from the centre line, 2 m off the edge
    EXPECT_FALSE(space.is_free(beside, 2.5, 0.0));  // asks for more
    EXPECT_FALSE(space.is_free({{50, 18.5}, {1, 0.4}, 0.0}, 0.0, 0.2));  // the actor corridor
    space.add_footprint(beside, 7);
    EXPECT_FALSE(space.is_free({{51, 6.5}, {1, 1}, 0.0}, 0.0, 0.0));
    space.remove_footprint(7);
    EXPECT_TRUE(space.is_free({{51, 6.5}, {1, 1}, 0.0}, 0.0, 0.0));
    EXPECT_NEAR(space.corridor_distance({30, 4}, 10.0), 4.0, 1e-12);
    EXPECT_NEAR(space.corridor_clearance({30, 4}, 10.0), 1.0, 1e-12);
    EXPECT_TRUE(std::isinf(space.corridor_distance({30, 40}, 10.0)));
}

}  // namespace
}  // namespace ltm::sim
