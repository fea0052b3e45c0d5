#include "evaluation/core/triangle_bvh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ltm::eval {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    // Voronoi regions of the vertices, edges and face (Ericson, Real-Time Collision Detection,
    // sec. 5.1.5). Degenerate triangles fall into a vertex or edge region, or are handled below.
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return a;
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) return a + (d1 / (d1 - d3)) * ab;
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) return a + (d2 / (d2 - d6)) * ac;
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0)
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    const double sum = va + vb + vc;
    if (sum > 1e-300) {
        const double v = vb / sum, w = vc / sum;
        return a + ab * v + ac * w;
    }
    // Degenerate (zero-area) triangle not caught above: nearest of its three edges.
    auto on_segment = [&p](const Eigen::Vector3d& s, const Eigen::Vector3d& e) {
        const Eigen::Vector3d d = e - s;
        const double l2 = d.squaredNorm();
        const double t = l2 > 0.0 ? std::clamp((p - s).dot(d) / l2, 0.0, 1.0) : 0.0;
        return Eigen::Vector3d(s + t * d);
    };
    Eigen::Vector3d best = on_segment(a, b);
    for (const Eigen::Vector3d& q : {on_segment(b, c), on_segment(a, c)})
        if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return best;
}

TriangleBvh::TriangleBvh(const std::vector<Eigen::Vector3d>& vertices,
                         const std::vector<Eigen::Vector3i>& triangles) {
    const auto nv = static_cast<int>(vertices.size());
    if (triangles.empty()) {
        for (const auto& v : vertices) tris_.push_back({v, v, v});
    } else {
        tris_.reserve(triangles.size());
        for (const auto& t : triangles) {
            if (t.minCoeff() < 0 || t.maxCoeff() >= nv) {
                ++dropped_;
                continue;
            }
            tris_.push_back({vertices[t[0]], vertices[t[1]], vertices[t[2]]});
        }
    }
    if (!tris_.empty()) {
        nodes_.reserve(2 * tris_.size() / 4 + 2);
        build(0, static_cast<std::uint32_t>(tris_.size()));
    }
}

std::int32_t TriangleBvh::build(std::uint32_t begin, std::uint32_t end) {
    const auto index = static_cast<std::int32_t>(nodes_.size());
    nodes_.emplace_back();
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo, clo = lo, chi = hi;
    for (std::uint32_t i = begin; i < end; ++i) {
        const Tri& t = tris_[i];
        lo = lo.cwiseMin(t.a).cwiseMin(t.b).cwiseMin(t.c);
        hi = hi.cwiseMax(t.a).cwiseMax(t.b).cwiseMax(t.c);
        const Eigen::Vector3d centre = (t.a + t.b + t.c) / 3.0;
        clo = clo.cwiseMin(centre);
        chi = chi.cwiseMax(centre);
    }
    nodes_[index].lo = lo;
    nodes_[index].hi = hi;
    constexpr std::uint32_t kLeafSize = 4;
    if (end - begin <= kLeafSize) {
        nodes_[index].begin = begin;
        nodes_[index].end = end;
        return index;
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(tris_.begin() + begin, tris_.begin() + mid, tris_.begin() + end,
                     [axis](const Tri& x, const Tri& y) {
                         return x.a[axis] + x.b[axis] + x.c[axis] <
                                y.a[axis] + y.b[axis] + y.c[axis];
                     });
    const std::int32_t left = build(begin, mid);
    const std::int32_t right = build(mid, end);
    nodes_[index].left = left;
    nodes_[index].right = right;
    return index;
}

double TriangleBvh::box_distance2(const Node& n, const Eigen::Vector3d& q) {
    const Eigen::Vector3d d = (n.lo - q).cwiseMax(q - n.hi).cwiseMax(0.0);
    return d.squaredNorm();
}

double TriangleBvh::distance(const Eigen::Vector3d& q) const {
    if (nodes_.empty()) return std::numeric_limits<double>::infinity();
    double best2 = std::numeric_limits<double>::infinity();
    std::vector<std::int32_t> stack{0};
    stack.reserve(64);
    while (!stack.empty()) {
        const Node& n = nodes_[stack.back()];
        stack.pop_back();
        if (box_distance2(n, q) >= best2) continue;
        if (n.left < 0) {
            for (std::uint32_t i = n.begin; i < n.end; ++i) {
                const Tri& t = tris_[i];
                best2 = std::min(best2,
                                 (closest_point_on_triangle(q, t.a, t.b, t.c) - q).squaredNorm());
            }
            continue;
        }
        // Visit the nearer child first (pushed last).
        const double dl = box_distance2(nodes_[n.left], q), dr = box_distance2(nodes_[n.right], q);
        if (dl < dr) {
            stack.push_back(n.right);
            stack.push_back(n.left);
        } else {
            stack.push_back(n.left);
            stack.push_back(n.right);
        }
    }
    return std::sqrt(best2);
}

}  // namespace ltm::eval
