#include "evaluation/core/svg_plot.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

TEST(SvgPlot, NiceTicks) {
    EXPECT_EQ(nice_ticks(0, 10, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
    const std::vector<double> t = nice_ticks(0.13, 0.87, 6);  // step 0.2
    ASSERT_EQ(t.size(), 4u);
    EXPECT_NEAR(t[0], 0.2, 1e-12);
    EXPECT_NEAR(t[3], 0.8, 1e-12);
    EXPECT_EQ(nice_ticks(-250, 250, 5), (std::vector<double>{-200, -100, 0, 100, 200}));
    EXPECT_TRUE(nice_ticks(1, 1).empty());
}

TEST(SvgPlot, RendersTitlesLegendAndEscapes) {
    PlotPanel p;
    p.title = "a < b & c";
    p.x_label = "x [m]";
    p.y_label = "y [m]";
    p.series.push_back({"truth", "#000", PlotSeries::Style::kDashed, 2.0, {{0, 0}, {1, 1}}});
    p.series.push_back(
        {"", "#f00", PlotSeries::Style::kSegments, 1.0, {{0, 0}, {1, 0}, {0, 1}, {1, 1}}});
    const std::string svg = render_svg({p, p}, 800, 400);
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
    EXPECT_NE(svg.find("a &lt; b &amp; c"), std::string::npos);
    EXPECT_NE(svg.find(">truth</text>"), std::string::npos);
    EXPECT_NE(svg.find("height=\"800\""), std::string::npos);  // two panels of 400 px
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
    // Two panels, two segments each.
    std::size_t lines = 0;
    for (std::size_t at = svg.find("stroke=\"#f00\""); at != std::string::npos;
         at = svg.find("stroke=\"#f00\"", at + 1))
        ++lines;
    EXPECT_EQ(lines, 4u);
    EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
}

}  // namespace
}  // namespace ltm::eval
