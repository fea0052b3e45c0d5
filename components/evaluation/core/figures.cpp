#include "evaluation/core/figures.hpp"

#include <algorithm>

#include "evaluation/core/svg_plot.hpp"

namespace ltm::eval {
namespace {

const char* kAxisName[3] = {"x", "y", "z"};

std::vector<Eigen::Vector2d> project(const common::PoseList& poses, int a, int b) {
    std::vector<Eigen::Vector2d> out;
    out.reserve(poses.size());
    for (const auto& p : poses) out.emplace_back(p.translation()[a], p.translation()[b]);
    return out;
}

}  // namespace

void plane_axes(TopViewPlane plane, const common::PoseList& poses, int& a, int& b) {
    switch (plane) {
        case TopViewPlane::kXY:
            a = 0, b = 1;
            return;
        case TopViewPlane::kXZ:
            a = 0, b = 2;
            return;
        case TopViewPlane::kYZ:
            a = 1, b = 2;
            return;
        case TopViewPlane::kAuto:
            break;
    }
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const auto& p : poses) {
        lo = lo.cwiseMin(p.translation());
        hi = hi.cwiseMax(p.translation());
    }
    int drop = 2;
    if (!poses.empty()) (hi - lo).minCoeff(&drop);
    a = drop == 0 ? 1 : 0;
    b = drop == 2 ? 1 : 2;
}

std::string trajectory_svg(const TrajectoryFigure& f) {
    int a = 0, b = 1;
    plane_axes(f.plane, f.reference.empty() ? f.estimate : f.reference, a, b);
    PlotPanel panel;
    panel.title = f.title;
    panel.x_label = std::string(kAxisName[a]) + " [m]";
    panel.y_label = std::string(kAxisName[b]) + " [m]";
    panel.equal_aspect = true;

    const std::vector<Eigen::Vector2d> ref = project(f.reference, a, b);
    const std::vector<Eigen::Vector2d> est = project(f.estimate, a, b);
    PlotSeries good{"loop (true)", "#2ca02c", PlotSeries::Style::kSegments, 1.4, {}};
    PlotSeries bad{"loop (false)", "#d62728", PlotSeries::Style::kSegments, 1.4, {}};
    PlotSeries any{"loop", "#9467bd", PlotSeries::Style::kSegments, 1.4, {}};
    for (std::size_t k = 0; k < f.loops.size(); ++k) {
        const auto& l = f.loops[k];
        if (l.query >= est.size() || l.match >= est.size()) continue;
        PlotSeries& s =
            f.loop_correct.size() == f.loops.size() ? (f.loop_correct[k] ? good : bad) : any;
        s.points.push_back(est[l.query]);
        s.points.push_back(est[l.match]);
    }
    // Thin links from each estimated pose to its true pose (at most ~200 of them).
    PlotSeries links{"position error", "#aaaaaa", PlotSeries::Style::kSegments, 1.0, {}};
    const std::size_t n = std::min(ref.size(), est.size());
    const std::size_t every = std::max<std::size_t>(1, n / 200);
    for (std::size_t i = 0; i < n; i += every) {
        links.points.push_back(est[i]);
        links.points.push_back(ref[i]);
    }
    if (!links.points.empty()) panel.series.push_back(links);
    panel.series.push_back({"ground truth", "#222222", PlotSeries::Style::kDashed, 2.0, ref});
    panel.series.push_back({"estimate (aligned)", "#1f77b4", PlotSeries::Style::kLine, 2.0, est});
    if (n <= 300) {  // few poses: show each one
        panel.series.push_back({"", "#222222", PlotSeries::Style::kMarkers, 2.5, ref});
        panel.series.push_back({"", "#1f77b4", PlotSeries::Style::kMarkers, 2.5, est});
    }
    // Loop edges, with a dot at each end so that short (correct) loops stay visible.
    for (PlotSeries* s : {&any, &good, &bad}) {
        if (s->points.empty()) continue;
        s->width = 2.0;
        panel.series.push_back(*s);
        panel.series.push_back({"", s->color, PlotSeries::Style::kMarkers, 3.5, s->points});
    }
    if (!ref.empty())
        panel.series.push_back(
            {"start", "#ff7f0e", PlotSeries::Style::kMarkers, 5.0, {ref.front()}});
    // Height follows the data's aspect (equal scales), between 300 and 800 px of plot.
    double xr = 1e-9, yr = 1e-9;
    if (!ref.empty() || !est.empty()) {
        Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
        for (const auto* list : {&ref, &est})
            for (const auto& q : *list) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
        xr = std::max(hi.x() - lo.x(), 1e-9);
        yr = std::max(hi.y() - lo.y(), 1e-9);
    }
    const double plot_w = 900 - 110;
    const double plot_h = std::clamp(plot_w * yr / xr, 300.0, 800.0);
    return render_svg({panel}, 900, static_cast<int>(plot_h + 135));
}

std::string errors_svg(const ErrorFigure& f) {
    PlotPanel top;
    top.title = f.title;
    top.x_label = "distance travelled [m]";
    top.y_label = "position error after alignment [m]";
    top.y_from_zero = true;
    PlotSeries ate{"absolute position error", "#1f77b4", PlotSeries::Style::kLine, 2.0, {}};
    for (std::size_t i = 0; i < std::min(f.distance.size(), f.position_error.size()); ++i)
        ate.points.emplace_back(f.distance[i], f.position_error[i]);
    top.series.push_back(ate);

    PlotPanel bottom;
    bottom.title = "Relative error from one frame to the next";
    bottom.x_label = "distance travelled [m]";
    bottom.y_label = "translation error per frame [cm]";
    bottom.y_from_zero = true;
    PlotSeries rpe{"relative translation error", "#d62728", PlotSeries::Style::kLine, 2.0, {}};
    for (std::size_t i = 0; i < f.step_translation.size() && i + 1 < f.distance.size(); ++i)
        rpe.points.emplace_back(f.distance[i + 1], 100.0 * f.step_translation[i]);
    bottom.series.push_back(rpe);

    PlotPanel rot;
    rot.title = "Relative rotation error from one frame to the next";
    rot.x_label = "distance travelled [m]";
    rot.y_label = "rotation error per frame [deg]";
    rot.y_from_zero = true;
    PlotSeries rr{"relative rotation error", "#9467bd", PlotSeries::Style::kLine, 2.0, {}};
    for (std::size_t i = 0; i < f.step_rotation_deg.size() && i + 1 < f.distance.size(); ++i)
        rr.points.emplace_back(f.distance[i + 1], f.step_rotation_deg[i]);
    rot.series.push_back(rr);
    return render_svg({top, bottom, rot}, 900, 380);
}

}  // namespace ltm::eval
