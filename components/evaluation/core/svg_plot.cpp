#include "evaluation/core/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace ltm::eval {
namespace {

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '"')
            out += "&quot;";
        else
            out += c;
    }
    return out;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

std::string tick_label(double v, double step) {
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 6),
                  std::abs(v) < step * 1e-6 ? 0.0 : v);
    return buf;
}

struct Box {
    double x0, y0, w, h;  // pixels
};

void draw_panel(std::ostringstream& svg, const PlotPanel& p, double top, int width, int height) {
    // Layout: title and legend above, y label on the left, x label below.
    const Box plot{80.0, top + 70.0, width - 110.0, height - 135.0};

    double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
    for (const auto& s : p.series)
        for (const auto& q : s.points) {
            if (!q.allFinite()) continue;
            xlo = std::min(xlo, q.x());
            xhi = std::max(xhi, q.x());
            ylo = std::min(ylo, q.y());
            yhi = std::max(yhi, q.y());
        }
    if (!(xlo <= xhi)) xlo = 0, xhi = 1, ylo = 0, yhi = 1;
    if (p.y_from_zero) ylo = std::min(ylo, 0.0), yhi = std::max(yhi, 0.0);
    if (xhi - xlo < 1e-9) xlo -= 0.5, xhi += 0.5;
    if (yhi - ylo < 1e-9) ylo -= 0.5, yhi += 0.5;
    // 4 % margins (none below a zero-based axis).
    const double mx = 0.04 * (xhi - xlo), my = 0.04 * (yhi - ylo);
    xlo -= mx, xhi += mx, yhi += my;
    if (!(p.y_from_zero && ylo == 0.0)) ylo -= my;
    if (p.equal_aspect) {
        const double sx = (xhi - xlo) / plot.w, sy = (yhi - ylo) / plot.h, s = std::max(sx, sy);
        const double cx = 0.5 * (xlo + xhi), cy = 0.5 * (ylo + yhi);
        xlo = cx - 0.5 * s * plot.w, xhi = cx + 0.5 * s * plot.w;
        ylo = cy - 0.5 * s * plot.h, yhi = cy + 0.5 * s * plot.h;
    }
    const auto px = [&](double x) { return plot.x0 + (x - xlo) / (xhi - xlo) * plot.w; };
    const auto py = [&](double y) { return plot.y0 + plot.h - (y - ylo) / (yhi - ylo) * plot.h; };

    svg << "<text x=\"" << num(width / 2.0) << "\" y=\"" << num(top + 26)
        << "\" font-size=\"18\" font-weight=\"bold\" text-anchor=\"middle\">" << escape(p.title)
        << "</text>\n";
    svg << "<rect x=\"" << num(plot.x0) << "\" y=\"" << num(plot.y0) << "\" width=\"" << num(plot.w)
        << "\" height=\"" << num(plot.h) << "\" fill=\"#ffffff\" stroke=\"#444\"/>\n";

    // Grid and ticks.
    const std::vector<double> xt = nice_ticks(xlo, xhi, p.equal_aspect ? 8 : 8);
    const std::vector<double> yt = nice_ticks(ylo, yhi, 6);
    const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
    const double ystep = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
    for (double x : xt) {
        svg << "<line x1=\"" << num(px(x)) << "\" y1=\"" << num(plot.y0) << "\" x2=\"" << num(px(x))
            << "\" y2=\"" << num(plot.y0 + plot.h) << "\" stroke=\"#e3e3e3\"/>\n";
        svg << "<text x=\"" << num(px(x)) << "\" y=\"" << num(plot.y0 + plot.h + 20)
            << "\" font-size=\"13\" text-anchor=\"middle\">" << tick_label(x, xstep) << "</text>\n";
    }
    for (double y : yt) {
        svg << "<line x1=\"" << num(plot.x0) << "\" y1=\"" << num(py(y)) << "\" x2=\""
            << num(plot.x0 + plot.w) << "\" y2=\"" << num(py(y)) << "\" stroke=\"#e3e3e3\"/>\n";
        svg << "<text x=\"" << num(plot.x0 - 8) << "\" y=\"" << num(py(y) + 4)
            << "\" font-size=\"13\" text-anchor=\"end\">" << tick_label(y, ystep) << "</text>\n";
    }
    svg << "<text x=\"" << num(plot.x0 + plot.w / 2) << "\" y=\"" << num(plot.y0 + plot.h + 45)
        << "\" font-size=\"15\" text-anchor=\"middle\">" << escape(p.x_label) << "</text>\n";
    const double ylx = 22, yly = plot.y0 + plot.h / 2;
    svg << "<text x=\"" << num(ylx) << "\" y=\"" << num(yly) << "\" font-size=\"15\" "
        << "text-anchor=\"middle\" transform=\"rotate(-90 " << num(ylx) << ' ' << num(yly) << ")\">"
        << escape(p.y_label) << "</text>\n";

    // Series, clipped to the plot box.
    const std::string clip = "clip" + std::to_string(static_cast<long>(top));
    svg << "<clipPath id=\"" << clip << "\"><rect x=\"" << num(plot.x0) << "\" y=\"" << num(plot.y0)
        << "\" width=\"" << num(plot.w) << "\" height=\"" << num(plot.h) << "\"/></clipPath>\n";
    svg << "<g clip-path=\"url(#" << clip << ")\">\n";
    for (const auto& s : p.series) {
        using Style = PlotSeries::Style;
        if (s.style == Style::kMarkers) {
            for (const auto& q : s.points)
                if (q.allFinite())
                    svg << "<circle cx=\"" << num(px(q.x())) << "\" cy=\"" << num(py(q.y()))
                        << "\" r=\"" << num(s.width) << "\" fill=\"" << s.color << "\"/>\n";
        } else if (s.style == Style::kSegments) {
            for (std::size_t i = 0; i + 1 < s.points.size(); i += 2)
                svg << "<line x1=\"" << num(px(s.points[i].x())) << "\" y1=\""
                    << num(py(s.points[i].y())) << "\" x2=\"" << num(px(s.points[i + 1].x()))
                    << "\" y2=\"" << num(py(s.points[i + 1].y())) << "\" stroke=\"" << s.color
                    << "\" stroke-width=\"" << num(s.width) << "\" stroke-opacity=\"0.8\"/>\n";
        } else if (!s.points.empty()) {
            svg << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\""
                << num(s.width) << "\" stroke-linejoin=\"round\""
                << (s.style == Style::kDashed ? " stroke-dasharray=\"7 4\"" : "") << " points=\"";
            for (const auto& q : s.points)
                if (q.allFinite()) svg << num(px(q.x())) << ',' << num(py(q.y())) << ' ';
            svg << "\"/>\n";
        }
    }
    svg << "</g>\n";

    // Legend: one row above the plot, right-aligned.
    double lx = plot.x0 + plot.w;
    const double ly = top + 52;
    for (auto it = p.series.rbegin(); it != p.series.rend(); ++it) {
        if (it->label.empty()) continue;
        const double text_w = 7.6 * static_cast<double>(it->label.size());
        lx -= text_w + 44;
        const double sx = lx, ex = lx + 28;
        if (it->style == PlotSeries::Style::kMarkers)
            svg << "<circle cx=\"" << num(sx + 14) << "\" cy=\"" << num(ly - 4) << "\" r=\""
                << num(std::max(3.0, it->width)) << "\" fill=\"" << it->color << "\"/>\n";
        else
            svg << "<line x1=\"" << num(sx) << "\" y1=\"" << num(ly - 4) << "\" x2=\"" << num(ex)
                << "\" y2=\"" << num(ly - 4) << "\" stroke=\"" << it->color
                << "\" stroke-width=\"3\""
                << (it->style == PlotSeries::Style::kDashed ? " stroke-dasharray=\"7 4\"" : "")
                << "/>\n";
        svg << "<text x=\"" << num(ex + 6) << "\" y=\"" << num(ly) << "\" font-size=\"13\">"
            << escape(it->label) << "</text>\n";
    }
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
    std::vector<double> ticks;
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || target < 1) return ticks;
    const double raw = (hi - lo) / target;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * mag >= raw) {
            step = m * mag;
            break;
        }
    for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step)
        ticks.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
    return ticks;
}

std::string render_svg(const std::vector<PlotPanel>& panels, int width, int panel_height) {
    std::ostringstream svg;
    const int height = panel_height * static_cast<int>(std::max<std::size_t>(1, panels.size()));
    svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" viewBox=\"0 0 " << width << ' ' << height << "\" font-family=\"DejaVu Sans, Arial, "
        << "sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"#fafafa\"/>\n";
    for (std::size_t i = 0; i < panels.size(); ++i)
        draw_panel(svg, panels[i], static_cast<double>(i) * panel_height, width, panel_height);
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace ltm::eval
