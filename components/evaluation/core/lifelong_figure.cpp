#include "evaluation/core/lifelong_figure.hpp"

#include <cmath>
#include <cstdio>

#include "evaluation/core/svg_plot.hpp"

namespace ltm::eval {
namespace {

// The footprint of o as four segments (kSegments: point pairs).
void add_outline(const SiteObject& o, std::vector<Eigen::Vector2d>& out) {
    const double yaw = o.yaw_deg * M_PI / 180.0;
    const Eigen::Vector2d c(o.x, o.y), u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
    const double a = 0.5 * o.length, b = 0.5 * o.width;
    const Eigen::Vector2d k[4] = {c + a * u + b * v, c - a * u + b * v, c - a * u - b * v,
                                  c + a * u - b * v};
    for (int i = 0; i < 4; ++i) {
        out.push_back(k[i]);
        out.push_back(k[(i + 1) % 4]);
    }
}

PlotSeries outlines(const std::vector<SiteObject>& objects, const std::string& label,
                    const std::string& colour) {
    PlotSeries s;
    s.label = objects.empty() ? "" : label + " (" + std::to_string(objects.size()) + ")";
    s.color = colour;
    s.style = PlotSeries::Style::kSegments;
    s.width = 1.6;
    for (const auto& o : objects) add_outline(o, s.points);
    return s;
}

std::string metres(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2g m", v);
    return text;
}

}  // namespace

std::string lifelong_day_svg(const LifelongDayFigure& f) {
    PlotPanel panel;
    panel.title = f.title;
    panel.x_label = "x [m]";
    panel.y_label = "y [m]";
    panel.equal_aspect = true;

    PlotSeries earlier{"earlier days (truth)", "#d0d0d0", PlotSeries::Style::kMarkers, 1.2, {}};
    for (const auto& p : f.earlier_paths) earlier.points.emplace_back(p.x(), p.y());
    PlotSeries truth{"truth, no map pose", "#404040", PlotSeries::Style::kMarkers, 1.0, {}};
    PlotSeries good{"error <= " + metres(f.good), "#2ca02c", PlotSeries::Style::kMarkers, 1.6, {}};
    PlotSeries fair{"error <= " + metres(f.wrong), "#ff7f0e", PlotSeries::Style::kMarkers, 1.8, {}};
    PlotSeries bad{"error > " + metres(f.wrong), "#d62728", PlotSeries::Style::kMarkers, 2.2, {}};
    for (std::size_t i = 0; i < f.truth.size(); ++i) {
        const double e = i < f.error.size() ? f.error[i] : -1.0;
        if (e < 0.0 || i >= f.aligned.size()) {
            truth.points.emplace_back(f.truth[i].translation().head<2>());
            continue;
        }
        const Eigen::Vector2d p = f.aligned[i].translation().head<2>();
        (e <= f.good ? good : (e <= f.wrong ? fair : bad)).points.push_back(p);
    }
    for (PlotSeries* s : {&earlier, &truth, &good, &fair, &bad})
        if (!s->points.empty()) panel.series.push_back(*s);
    for (const auto& s : {outlines(f.changes.removed, "removed", "#d62728"),
                          outlines(f.changes.moved_from, "moved: old place", "#9467bd"),
                          outlines(f.changes.moved_to, "moved: new place", "#17becf"),
                          outlines(f.changes.added, "added", "#2ca02c")})
        if (!s.points.empty()) panel.series.push_back(s);
    return render_svg({panel}, 1000, 760);
}

}  // namespace ltm::eval
