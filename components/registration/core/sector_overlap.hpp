#pragma once
// How much of a scan a map explains, direction by direction (issue 26): the scan's points are split
// into azimuth sectors about the sensor (the first centred on its x axis) and each sector holding
// at least `min_share` of the points gets its own explained share (points whose |IMLS distance|
// to the map is within the inlier distance). At a map's edge the side towards the map is explained
// and the side beyond it is not, while the share over the whole scan can still look fine; a
// registration there is pulled along the road towards the map. The loop verification
// (LoopVerification::min_sector_fraction) and the localisation's tracking (edge_sector_overlap)
// both judge by the weakest sector.
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "registration/core/imls.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::registration {

struct SectorOverlap {
    double min_fraction = 1.0;  // explained share in the weakest sector (1: no sector counted)
    double weakest_deg = 0.0;   // that sector's centre, deg from the LiDAR's x axis towards y
};

// Counts points and explained points per sector, then names the weakest.
class SectorCounter {
  public:
    explicit SectorCounter(int sectors);
    void add(const Eigen::Vector3f& p_lidar, bool explained);
    SectorOverlap weakest(double min_share) const;

  private:
    double width_;  // [rad]
    std::size_t total_ = 0;
    std::vector<std::size_t> points_, explained_;
};

// The points (LiDAR frame) at T_grid_lidar against the grid: explained when the IMLS distance
// exists and is within inlier_distance.
SectorOverlap sector_overlap(const std::vector<Eigen::Vector3f>& points, const VoxelGrid& grid,
                             const Eigen::Isometry3d& T_grid_lidar, const ImlsParams& imls,
                             double inlier_distance, int sectors, double min_share);

}  // namespace ltm::registration
