#include "evaluation/core/top_view_image.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

TEST(TopViewImage, FitsPointsAndPathsIntoTheImage) {
    TopViewLayer map;
    for (int i = 0; i <= 100; ++i) map.points.emplace_back(0.1f * i, 0.0f, 1.0f);  // 10 m along x
    map.points.emplace_back(NAN, 0.0f, 0.0f);                                      // left out
    TopViewLayer changes;
    changes.points = {Eigen::Vector3f(5.0f, 5.0f, 0.0f)};
    changes.colours = {{214, 39, 40}};
    TopViewPath path;
    path.positions = {Eigen::Vector3d(0, 2, 0), Eigen::Vector3d(10, 2, 0)};
    path.colour = {0, 0, 255};
    const TopView view = render_top_view({map, changes}, {path}, 200);
    ASSERT_GT(view.image.width, 0);
    EXPECT_LE(std::max(view.image.width, view.image.height), 201);
    EXPECT_EQ(view.points_drawn, 102u);
    EXPECT_GT(view.metres_per_pixel, 0.0);
    auto pixel = [&](double x, double y) {
        const int px = static_cast<int>(std::floor((x - view.min_xy.x()) / view.metres_per_pixel));
        const int py = view.image.height - 1 -
                       static_cast<int>(std::floor((y - view.min_xy.y()) / view.metres_per_pixel));
        return view.image.at(px, py);
    };
    EXPECT_EQ(pixel(5.0, 5.0), (Rgb{214, 39, 40}));  // the change in its colour
    EXPECT_EQ(pixel(3.0, 2.0), (Rgb{0, 0, 255}));    // the path drawn over
    const Rgb grey = pixel(3.0, 0.0);                // the map: darker than the background
    EXPECT_LT(grey[0], 200);
    EXPECT_EQ(grey[0], grey[1]);
    EXPECT_EQ(view.image.at(0, 0), (Rgb{255, 255, 255}));
}

TEST(TopViewImage, NothingToDrawGivesAnEmptyImage) {
    TopViewLayer nothing;
    nothing.points = {Eigen::Vector3f(NAN, NAN, NAN)};
    EXPECT_EQ(render_top_view({nothing}, {}).image.width, 0);
    EXPECT_EQ(render_top_view({}, {}).image.width, 0);
}

}  // namespace
}  // namespace ltm::eval
