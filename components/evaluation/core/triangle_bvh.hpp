#pragma once
// Nearest-surface queries over a triangle soup: a bounding-volume hierarchy (median split on the
// longest axis) with exact point-triangle distances.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace ltm::eval {

// Closest point to p on triangle (a, b, c); degenerate triangles (segments, points) allowed.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c);

class TriangleBvh {
  public:
    // Triangles index `vertices`; triangles with an index out of range are dropped (see
    // dropped()). With no triangles, every vertex is a point of the surface.
    TriangleBvh(const std::vector<Eigen::Vector3d>& vertices,
                const std::vector<Eigen::Vector3i>& triangles);

    bool empty() const { return tris_.empty(); }
    std::size_t dropped() const { return dropped_; }
    // Distance from q to the nearest surface point; +infinity when empty.
    double distance(const Eigen::Vector3d& q) const;

  private:
    struct Tri {
        Eigen::Vector3d a, b, c;
    };
    struct Node {
        Eigen::Vector3d lo, hi;
        std::int32_t left = -1, right = -1;  // children, or -1 for a leaf
        std::uint32_t begin = 0, end = 0;    // leaf: tris_[begin, end)
    };
    std::int32_t build(std::uint32_t begin, std::uint32_t end);
    static double box_distance2(const Node& n, const Eigen::Vector3d& q);

    std::vector<Tri> tris_;
    std::vector<Node> nodes_;
    std::size_t dropped_ = 0;
};

}  // namespace ltm::eval
