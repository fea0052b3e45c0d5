#include "evaluation/core/new_ground.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

std::vector<Eigen::Vector3d> line(double x0, double y0, double x1, double y1, int n) {
    std::vector<Eigen::Vector3d> out;
    for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        out.emplace_back(x0 + t * (x1 - x0), y0 + t * (y1 - y0), 0.0);
    }
    return out;
}

TEST(NewGround, FirstDayIsAllNew) {
    EXPECT_NEAR(new_ground(line(0, 0, 100, 0, 500), {}, {}).driven, 100.0, 1e-9);
}

TEST(NewGround, OnlyTheStretchBeyondTheRadiusCounts) {
    const auto earlier = line(0, 0, 50, 0, 250);
    // 0..100 m along x: points beyond x = 60 are more than 10 m from the earlier path.
    const double n = new_ground(line(0, 0, 100, 0, 1000), earlier, {}).driven;
    EXPECT_NEAR(n, 40.0, 0.2);
    // A parallel road 5 m away (height ignored) is not new; 15 m away it is.
    auto beside = line(0, 5, 50, 5, 250);
    for (auto& p : beside) p.z() = 30.0;
    EXPECT_NEAR(new_ground(beside, earlier, {}).driven, 0.0, 1e-9);
    EXPECT_NEAR(new_ground(line(0, 15, 50, 15, 250), earlier, {}).driven, 50.0, 1e-9);
}

TEST(NewGround, JumpsAreNotRoad) {
    auto path = line(0, 100, 20, 100, 100);
    const auto after = line(200, 100, 220, 100, 100);  // a kidnap 180 m on
    path.insert(path.end(), after.begin(), after.end());
    EXPECT_NEAR(new_ground(path, {}, {}).driven, 40.0, 1e-9);
}

TEST(NewGround, MappedWhereTheMapHasVoxelsNearThePath) {
    const auto path = line(0, 0, 100, 0, 500);
    // Ground voxels 1 m below the first 40 m of the path only.
    auto map = line(0, 0, 40, 0, 80);
    for (auto& p : map) p.z() = -1.0;
    const NewGround g = new_ground(path, {}, map);
    EXPECT_NEAR(g.driven, 100.0, 1e-9);
    EXPECT_NEAR(g.mapped, 41.1, 0.3);  // voxels 1 m below reach 1.1 m beyond x = 40
    EXPECT_EQ(new_ground(path, path, map).mapped, 0.0);  // mapped, but not new
}

}  // namespace
}  // namespace ltm::eval
