#include "evaluation/core/lifelong_figure.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

Eigen::Isometry3d at(double x, double y) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    return T;
}

TEST(LifelongFigure, DrawsErrorBandsAndChanges) {
    LifelongDayFigure f;
    f.title = "day 2";
    f.earlier_paths = {{0, 0, 0}, {1, 0, 0}};
    for (int i = 0; i < 4; ++i) {
        f.truth.push_back(at(i, 1));
        f.aligned.push_back(at(i, 1));
    }
    f.error = {0.05, 0.3, 0.9, -1.0};  // good, fair, wrong, no pose
    SiteObject o;
    o.x = 2, o.y = 2, o.length = 4, o.width = 2, o.height = 1;
    f.changes.removed = {o};
    const std::string svg = lifelong_day_svg(f);
    EXPECT_NE(svg.find("<svg"), std::string::npos);
    for (const char* label : {"day 2", "earlier days (truth)", "truth, no map pose",
                              "error &lt;= 0.1 m", "error &gt; 0.5 m", "removed (1)"})
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    EXPECT_EQ(svg.find("added ("), std::string::npos);
}

}  // namespace
}  // namespace ltm::eval
