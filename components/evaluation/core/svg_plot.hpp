#pragma once
// Plain SVG charts (no dependency): x-y line/marker/segment series with ticked axes, axis labels,
// title and legend. Returns SVG text; writing it to a file is the caller's business.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace ltm::eval {

struct PlotSeries {
    enum class Style {
        kLine,
        kDashed,
        kMarkers,
        kSegments
    };                              // kSegments: points (0,1), (2,3), ...
    std::string label;              // legend text; empty: not in the legend
    std::string color = "#1f77b4";  // any SVG colour
    Style style = Style::kLine;
    double width = 1.8;  // [px] line width, or marker radius
    std::vector<Eigen::Vector2d> points;
};

struct PlotPanel {
    std::string title, x_label, y_label;
    bool equal_aspect = false;  // same metres per pixel on both axes (top views)
    bool y_from_zero = false;   // include y = 0 (error plots)
    std::vector<PlotSeries> series;
};

// Panels stacked vertically, each `panel_height` px high, `width` px wide.
std::string render_svg(const std::vector<PlotPanel>& panels, int width = 900,
                       int panel_height = 600);

// "Nice" tick values (1, 2, 5 x 10^k steps) covering [lo, hi], about `target` of them.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

}  // namespace ltm::eval
