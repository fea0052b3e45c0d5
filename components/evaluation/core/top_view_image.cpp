#include "evaluation/core/top_view_image.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::eval {

void RgbImage::fill(int w, int h, Rgb colour) {
    width = w;
    height = h;
    rgb.resize(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < rgb.size(); i += 3)
        std::copy(colour.begin(), colour.end(), &rgb[i]);
}

void RgbImage::set(int x, int y, Rgb colour) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::copy(colour.begin(), colour.end(), &rgb[(static_cast<std::size_t>(y) * width + x) * 3]);
}

Rgb RgbImage::at(int x, int y) const {
    const std::uint8_t* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    return {p[0], p[1], p[2]};
}

namespace {

bool finite(const Eigen::Vector3f& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

struct Frame {
    Eigen::Vector2d min_xy;
    double scale = 1.0;  // pixels a metre
    int height = 0;
    int px(double x) const { return static_cast<int>(std::floor((x - min_xy.x()) * scale)); }
    int py(double y) const {
        return height - 1 - static_cast<int>(std::floor((y - min_xy.y()) * scale));
    }
};

void draw_line(RgbImage& image, int x0, int y0, int x1, int y1, Rgb colour) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    for (int guard = 0; guard < 100000; ++guard) {
        for (int ox = 0; ox <= 1; ++ox) {  // two pixels wide
            for (int oy = 0; oy <= 1; ++oy) image.set(x0 + ox, y0 + oy, colour);
        }
        if (x0 == x1 && y0 == y1) return;
        const int e2 = 2 * err;
        if (e2 >= dy) {
            err += dy;
            x0 += sx;
        }
        if (e2 <= dx) {
            err += dx;
            y0 += sy;
        }
    }
}

}  // namespace

TopView render_top_view(const std::vector<TopViewLayer>& layers,
                        const std::vector<TopViewPath>& paths, int max_size) {
    TopView view;
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const TopViewLayer& l : layers) {
        for (const Eigen::Vector3f& p : l.points) {
            if (!finite(p)) continue;
            lo = lo.cwiseMin(p.head<2>().cast<double>());
            hi = hi.cwiseMax(p.head<2>().cast<double>());
        }
    }
    for (const TopViewPath& path : paths) {
        for (const Eigen::Vector3d& p : path.positions) {
            if (!std::isfinite(p.x()) || !std::isfinite(p.y())) continue;
            lo = lo.cwiseMin(p.head<2>());
            hi = hi.cwiseMax(p.head<2>());
        }
    }
    if (!(lo.x() <= hi.x()) || max_size < 16) return view;
    const double margin = 0.02 * std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1.0});
    lo -= Eigen::Vector2d::Constant(margin);
    hi += Eigen::Vector2d::Constant(margin);
    const double extent = std::max(hi.x() - lo.x(), hi.y() - lo.y());
    Frame f;
    f.min_xy = lo;
    f.scale = max_size / extent;
    const int width = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) * f.scale)));
    f.height = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) * f.scale)));
    view.image.fill(width, f.height, {255, 255, 255});
    view.metres_per_pixel = 1.0 / f.scale;
    view.min_xy = lo;

    for (const TopViewLayer& l : layers) {
        if (!l.colours.empty() && l.colours.size() == l.points.size()) {
            for (std::size_t i = 0; i < l.points.size(); ++i) {
                if (!finite(l.points[i])) continue;
                view.image.set(f.px(l.points[i].x()), f.py(l.points[i].y()), l.colours[i]);
                ++view.points_drawn;
            }
            continue;
        }
        // Density: the layer's colour at full strength where the most points pile up (log scale).
        std::vector<std::uint32_t> count(static_cast<std::size_t>(width) * f.height, 0);
        std::uint32_t most = 0;
        for (const Eigen::Vector3f& p : l.points) {
            if (!finite(p)) continue;
            const int x = f.px(p.x()), y = f.py(p.y());
            if (x < 0 || y < 0 || x >= width || y >= f.height) continue;
            most = std::max(most, ++count[static_cast<std::size_t>(y) * width + x]);
            ++view.points_drawn;
        }
        const double log_most = std::log1p(static_cast<double>(most));
        for (int y = 0; y < f.height; ++y) {
            for (int x = 0; x < width; ++x) {
                const std::uint32_t n = count[static_cast<std::size_t>(y) * width + x];
                if (n == 0) continue;
                const double a = 0.55 + 0.45 * std::log1p(static_cast<double>(n)) / log_most;
                const Rgb under = view.image.at(x, y);
                Rgb c;
                for (int k = 0; k < 3; ++k) {
                    c[k] = static_cast<std::uint8_t>(
                        std::lround((1.0 - a) * under[k] + a * l.colour[k]));
                }
                view.image.set(x, y, c);
            }
        }
    }
    for (const TopViewPath& path : paths) {
        for (std::size_t i = 1; i < path.positions.size(); ++i) {
            const Eigen::Vector3d& a = path.positions[i - 1];
            const Eigen::Vector3d& b = path.positions[i];
            if (!a.allFinite() || !b.allFinite()) continue;
            draw_line(view.image, f.px(a.x()), f.py(a.y()), f.px(b.x()), f.py(b.y()), path.colour);
        }
    }
    return view;
}

}  // namespace ltm::eval
