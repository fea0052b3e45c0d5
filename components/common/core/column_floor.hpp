#pragma once
// The lowest point of each vertical column of a horizontal lattice, and the lowest within a
// neighbourhood of columns: where the ground is under a voxel. Maintenance's ground removal
// (maintenance/core/ground.cpp) and the mapping's ground guard on map edits
// (mapping/core/mapper_map_edits.cpp) ask it the same question of their own voxels.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>

namespace ltm::common {

class ColumnFloor {
  public:
    // Columns of edge `column_size` (> 0) [m] on the x-y lattice through the origin.
    explicit ColumnFloor(float column_size, std::size_t expected_columns = 0);

    // Lowers p's column's floor to p.z() (non-finite points are skipped).
    void add(const Eigen::Vector3f& p);
    // The lowest z of the columns within `cells` columns of p's (each way, a square);
    // +infinity when none of them holds a point.
    float lowest_around(const Eigen::Vector3f& p, int cells) const;

  private:
    Eigen::Vector2i column(const Eigen::Vector3f& p) const;
    static std::uint64_t key(int x, int y);

    float inv_size_;
    std::unordered_map<std::uint64_t, float> lowest_;
};

}  // namespace ltm::common
