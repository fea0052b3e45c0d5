#include "simulator/core/geometry2d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ltm::sim {
namespace {

Eigen::Vector2d left_normal(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }
double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

bool segments_intersect(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2,
                        const Eigen::Vector2d& q1, const Eigen::Vector2d& q2) {
    const double d1 = cross2(q2 - q1, p1 - q1), d2 = cross2(q2 - q1, p2 - q1);
    const double d3 = cross2(p2 - p1, q1 - p1), d4 = cross2(p2 - p1, q2 - p1);
    return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

}  // namespace

Polyline::Polyline(Points2 points) : points_(std::move(points)) {
    cumulative_.resize(points_.size());
    double s = 0.0;
    for (std::size_t i = 0; i < points_.size(); ++i) {
        if (i > 0) s += (points_[i] - points_[i - 1]).norm();
        cumulative_[i] = s;
    }
}

std::size_t Polyline::segment_at(double s) const {
    if (points_.size() < 2) return 0;
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
    const std::size_t i = static_cast<std::size_t>(it - cumulative_.begin());
    return std::min(i == 0 ? 0 : i - 1, points_.size() - 2);
}

Eigen::Vector2d Polyline::point_at(double s) const {
    if (points_.empty()) return Eigen::Vector2d::Zero();
    if (points_.size() == 1) return points_[0];
    s = std::clamp(s, 0.0, length());
    const std::size_t i = segment_at(s);
    const double len = cumulative_[i + 1] - cumulative_[i];
    const double f = len > 0 ? (s - cumulative_[i]) / len : 0.0;
    return points_[i] + f * (points_[i + 1] - points_[i]);
}

Eigen::Vector2d Polyline::tangent_at(double s) const {
    if (points_.size() < 2) return Eigen::Vector2d::UnitX();
    std::size_t i = segment_at(std::clamp(s, 0.0, length()));
    // Skip zero-length segments.
    while (i + 1 < points_.size() - 1 && (points_[i + 1] - points_[i]).norm() == 0.0) ++i;
    const Eigen::Vector2d d = points_[i + 1] - points_[i];
    return d.norm() > 0 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::UnitX();
}

double Polyline::project(const Eigen::Vector2d& p) const {
    double best = std::numeric_limits<double>::max(), best_s = 0.0;
    for (std::size_t i = 0; i + 1 < points_.size(); ++i) {
        const Eigen::Vector2d ab = points_[i + 1] - points_[i];
        const double l2 = ab.squaredNorm();
        const double f = l2 > 0 ? std::clamp((p - points_[i]).dot(ab) / l2, 0.0, 1.0) : 0.0;
        const double d = (points_[i] + f * ab - p).squaredNorm();
        if (d < best) {
            best = d;
            best_s = cumulative_[i] + f * std::sqrt(l2);
        }
    }
    return best_s;
}

Points2 round_corners(const Points2& in, double radius, double step,
                      std::vector<std::size_t>* vertex_index) {
    Points2 pts;
    std::vector<std::size_t> dedup(in.size(), 0);  // input index -> index in pts
    for (std::size_t i = 0; i < in.size(); ++i) {
        if (pts.empty() || (in[i] - pts.back()).norm() > 1e-9) pts.push_back(in[i]);
        dedup[i] = pts.size() - 1;
    }
    std::vector<std::size_t> out_of(pts.size(), 0);  // index in pts -> output index
    Points2 out;
    if (!pts.empty()) out.push_back(pts.front());
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
        const Eigen::Vector2d a = pts[i - 1], b = pts[i], c = pts[i + 1];
        const Eigen::Vector2d d1 = (b - a).normalized(), d2 = (c - b).normalized();
        const double turn = std::acos(std::clamp(d1.dot(d2), -1.0, 1.0));
        if (radius <= 0 || turn < 1e-3 || turn > M_PI - 1e-3) {
            out.push_back(b);
            out_of[i] = out.size() - 1;
            continue;
        }
        double tangent = radius * std::tan(turn / 2);
        tangent = std::min(tangent, 0.5 * std::min((b - a).norm(), (c - b).norm()));
        const double r = tangent / std::tan(turn / 2);
        const Eigen::Vector2d start = b - d1 * tangent;
        const double side = cross2(d1, d2) > 0 ? 1.0 : -1.0;
        const Eigen::Vector2d center = start + side * r * left_normal(d1);
        const int n = std::max(2, static_cast<int>(std::ceil(r * turn / step)));
        const Eigen::Vector2d v0 = start - center;
        for (int k = 0; k <= n; ++k) {
            const double ang = side * turn * k / n;
            const double cs = std::cos(ang), sn = std::sin(ang);
            const Eigen::Vector2d p =
                center + Eigen::Vector2d(cs * v0.x() - sn * v0.y(), sn * v0.x() + cs * v0.y());
            if ((p - out.back()).norm() > 1e-9) out.push_back(p);
            if (k == n / 2) out_of[i] = out.size() - 1;
        }
    }
    if (pts.size() > 1) {
        if ((pts.back() - out.back()).norm() > 1e-9) out.push_back(pts.back());
        out_of[pts.size() - 1] = out.size() - 1;
    }
    if (vertex_index) {
        vertex_index->resize(in.size());
        for (std::size_t i = 0; i < in.size(); ++i) (*vertex_index)[i] = out_of[dedup[i]];
    }
    return out;
}

Points2 offset_polyline(const Points2& pts, double d) {
    Points2 out;
    const std::size_t n = pts.size();
    if (n < 2) return pts;
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector2d prev = i > 0 ? Eigen::Vector2d((pts[i] - pts[i - 1]).normalized())
                                           : Eigen::Vector2d((pts[1] - pts[0]).normalized());
        const Eigen::Vector2d next =
            i + 1 < n ? Eigen::Vector2d((pts[i + 1] - pts[i]).normalized()) : prev;
        const Eigen::Vector2d n0 = left_normal(prev), n1 = left_normal(next);
        Eigen::Vector2d m = n0 + n1;
        if (m.norm() < 1e-6) {
            m = n0;
        } else {
            m.normalize();
        }
        const double cos_half = std::max(m.dot(n0), 1.0 / 3.0);  // mitre at most 3 d
        out.push_back(pts[i] + m * (d / cos_half));
    }
    return out;
}

Eigen::Vector2d OrientedRect::axis_x() const { return {std::cos(yaw), std::sin(yaw)}; }
Eigen::Vector2d OrientedRect::axis_y() const { return {-std::sin(yaw), std::cos(yaw)}; }

Eigen::Vector2d OrientedRect::corner(int k) const {
    const double sx = (k == 0 || k == 3) ? -1.0 : 1.0;
    const double sy = (k < 2) ? -1.0 : 1.0;
    return center + sx * half.x() * axis_x() + sy * half.y() * axis_y();
}

bool OrientedRect::contains(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d d = p - center;
    return std::abs(d.dot(axis_x())) <= half.x() && std::abs(d.dot(axis_y())) <= half.y();
}

bool rects_overlap(const OrientedRect& a, const OrientedRect& b, double margin) {
    const Eigen::Vector2d axes[4] = {a.axis_x(), a.axis_y(), b.axis_x(), b.axis_y()};
    const Eigen::Vector2d d = b.center - a.center;
    for (const auto& u : axes) {
        const double ra =
            a.half.x() * std::abs(a.axis_x().dot(u)) + a.half.y() * std::abs(a.axis_y().dot(u));
        const double rb =
            b.half.x() * std::abs(b.axis_x().dot(u)) + b.half.y() * std::abs(b.axis_y().dot(u));
        if (std::abs(d.dot(u)) >= ra + rb + 2.0 * margin)
            return false;  // touching is not overlapping
    }
    return true;
}

double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b) {
    const Eigen::Vector2d ab = b - a;
    const double l2 = ab.squaredNorm();
    const double f = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    return (a + f * ab - p).norm();
}

double segment_rect_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const OrientedRect& r) {
    if (r.contains(a) || r.contains(b)) return 0.0;
    double best = std::numeric_limits<double>::max();
    for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d c0 = r.corner(k), c1 = r.corner((k + 1) % 4);
        if (segments_intersect(a, b, c0, c1)) return 0.0;
        best = std::min({best, point_segment_distance(c0, a, b), point_segment_distance(a, c0, c1),
                         point_segment_distance(b, c0, c1)});
    }
    return best;
}

}  // namespace ltm::sim
