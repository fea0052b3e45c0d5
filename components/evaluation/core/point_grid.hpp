#pragma once
// A hash grid of points for fixed-radius queries (cell size = the radius).
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace ltm::eval {

class PointGrid {
  public:
    // radius > 0 [m]. The points are copied.
    PointGrid(const std::vector<Eigen::Vector3f>& points, double radius);

    // True when some point lies within the radius (inclusive) of q.
    bool has_neighbour(const Eigen::Vector3f& q) const;
    // Distance to the nearest point if it is within the radius, otherwise a negative value.
    double nearest_within(const Eigen::Vector3f& q) const;

  private:
    std::int64_t key(const Eigen::Vector3i& c) const;
    Eigen::Vector3i cell(const Eigen::Vector3f& p) const;

    double radius_;
    std::vector<Eigen::Vector3f> points_;
    std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace ltm::eval
