#pragma once
// Plane geometry for layouts and paths: arc-length polylines, rounded corners, offsets and
// oriented rectangles (object footprints).
#include <Eigen/Core>
#include <vector>

namespace ltm::sim {

using Points2 = std::vector<Eigen::Vector2d, Eigen::aligned_allocator<Eigen::Vector2d>>;

// A polyline parametrised by arc length s in [0, length()].
class Polyline {
  public:
    Polyline() = default;
    explicit Polyline(Points2 points);

    const Points2& points() const { return points_; }
    double length() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }
    // Arc length at vertex i.
    double vertex_s(std::size_t i) const { return cumulative_[i]; }
    Eigen::Vector2d point_at(double s) const;    // clamped to the ends
    Eigen::Vector2d tangent_at(double s) const;  // unit
    std::size_t segment_at(double s) const;      // index of the segment holding s
    // Arc length of the point of the polyline nearest to p (brute force; for set-up only).
    double project(const Eigen::Vector2d& p) const;

  private:
    Points2 points_;
    std::vector<double> cumulative_;
};

// Replaces every inner corner by a circular arc of radius at most `radius` (less where the
// neighbouring segments are short), sampled every `step` metres. Duplicate points are dropped.
// `vertex_index`, when given, receives for every input point the index of the output point
// standing for it (the middle of its arc).
Points2 round_corners(const Points2& points, double radius, double step = 0.5,
                      std::vector<std::size_t>* vertex_index = nullptr);

// The polyline shifted sideways by `d` metres (positive: to the left of the direction of
// travel), with mitred joints.
Points2 offset_polyline(const Points2& points, double d);

// A footprint: centre, half sizes along its own axes, heading [rad].
struct OrientedRect {
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    Eigen::Vector2d half = Eigen::Vector2d::Zero();
    double yaw = 0.0;

    Eigen::Vector2d axis_x() const;
    Eigen::Vector2d axis_y() const;
    // Corner k in 0..3, counter-clockwise.
    Eigen::Vector2d corner(int k) const;
    bool contains(const Eigen::Vector2d& p) const;
};

// True when the two rectangles, each inflated by `margin`, overlap (separating axes).
bool rects_overlap(const OrientedRect& a, const OrientedRect& b, double margin);
// Distance from a segment to a rectangle (0 when they intersect).
double segment_rect_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const OrientedRect& r);
double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                              const Eigen::Vector2d& b);

}  // namespace ltm::sim
