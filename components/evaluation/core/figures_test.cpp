#include "evaluation/core/figures.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

common::PoseList line(const Eigen::Vector3d& step, int n) {
    common::PoseList out;
    for (int i = 0; i < n; ++i) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = step * i + Eigen::Vector3d(0, 0.1 * (i % 2), 0.2 * (i % 3));
        out.push_back(T);
    }
    return out;
}

TEST(Figures, AutoPlaneDropsTheFlattestAxis) {
    int a = -1, b = -1;
    // Extends along x and z (a KITTI camera-frame drive), hardly along y.
    plane_axes(TopViewPlane::kAuto, line({1, 0, 2}, 10), a, b);
    EXPECT_EQ(a, 0);
    EXPECT_EQ(b, 2);
    plane_axes(TopViewPlane::kXY, {}, a, b);
    EXPECT_EQ(b, 1);
}

TEST(Figures, TrajectoryShowsSeriesAndColouredLoops) {
    TrajectoryFigure f;
    f.reference = line({1, 1, 0}, 20);
    f.estimate = line({1, 1.1, 0}, 20);
    f.loops = {{15, 2, 0}, {19, 0, 0}};
    f.loop_correct = {true, false};
    const std::string svg = trajectory_svg(f);
    EXPECT_NE(svg.find(">ground truth</text>"), std::string::npos);
    EXPECT_NE(svg.find(">estimate (aligned)</text>"), std::string::npos);
    EXPECT_NE(svg.find(">loop (true)</text>"), std::string::npos);
    EXPECT_NE(svg.find(">loop (false)</text>"), std::string::npos);
    EXPECT_NE(svg.find("x [m]"), std::string::npos);
}

TEST(Figures, ErrorsHaveThreePanels) {
    ErrorFigure f;
    f.distance = {0, 1, 2};
    f.position_error = {0.1, 0.2, 0.1};
    f.step_translation = {0.01, 0.02};
    f.step_rotation_deg = {0.1, 0.2};
    const std::string svg = errors_svg(f);
    EXPECT_NE(svg.find("distance travelled [m]"), std::string::npos);
    EXPECT_NE(svg.find("translation error per frame [cm]"), std::string::npos);
    EXPECT_NE(svg.find("rotation error per frame [deg]"), std::string::npos);
    EXPECT_EQ(std::count(svg.begin(), svg.end(), '\n') > 20, true);
}

}  // namespace
}  // namespace ltm::eval
