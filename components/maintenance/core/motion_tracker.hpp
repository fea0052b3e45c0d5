#pragma once
// Objects that move within a short window, found scan against scan (issue 26 item 5): what the
// voxels' view histories cannot tell in a second. A walker moving 1 m in 1 s keeps being hit in
// the voxels it spans; no view sees through them, and a motorcyclist joined to the road's
// segment cannot leave with its segment. Positive evidence instead: the same shape, displaced.
//
// Per scan (world frame): its points in cells of `cell`; the ground (cells within ground_height
// of the ground level of their 3 x 3 column neighbourhood: the second lowest of its columns'
// lowest cells, so that a reflection metres below the road is not the level); the other cells
// clustered (cells within `neighbourhood` cells of each other, twice that vertically, whose
// points' means are within join_distance horizontally: a walker 0.3 m in front of a hedge is
// on the cells next to the hedge's, and one cluster with it would be 14 m long, not an object);
// clusters of object size (min_cells..max_cells, at most max_extent wide and max_height tall)
// are followed.
// Each cluster is linked to the cluster of the newest of the last scans (up to 0.35 s back)
// that is it rigidly displaced by the least (similar box and height; after nearest-cell
// iterations from the centroids' difference, at least min_match of the cells of each within
// match_distance of the other's, within max_speed x lag): the same object. It is moving when
//   - its oldest linked ancestor min_lag..max_lag s earlier is it displaced by at least
//     min_shift (horizontally) as a rigid shape (the same match), and
//   - its place now was not occupied then, nor the ancestor's place now (at most max_overlap of
//     the cells the other scan saw: a point in the cell or a return at it, within a view's
//     margin), and one of the two was seen empty (at least min_known of its cells seen
//     through; the other may be hidden: an object moving along the beams hides its own place
//     ahead of it).
// A parked car seen from a passing car changes its visible side, not its place: its cells are
// occupied (or hidden) in the other scan, never empty. A moving cluster's points are returned,
// with those of the clusters its chain links it to and of the clusters that link to it later,
// as far as each link moved at least min_shift / max_lag (a link that stood still ends the
// chain). A cluster's points include its feet: the ground cells in its cells' columns just
// below it (a motorcycle's wheels are within the ground's height of the road); they are not
// matched. The caller flags their voxels (LongTermMap; a voxel of the map's ground stays).
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"
#include "maintenance/core/range_image.hpp"

namespace ltm::maintenance {

struct MotionStats {
    std::size_t scans = 0, clusters = 0, compared = 0, moving = 0;  // moving: cluster pairs
};

class MotionTracker {
  public:
    // Points farther than max_range [m] from the sensor are not used.
    MotionTracker(const MotionConfig& config, const RangeImageConfig& image, double max_range);
    ~MotionTracker();
    MotionTracker(MotionTracker&&) noexcept;
    MotionTracker& operator=(MotionTracker&&) noexcept;

    // A registered scan (points in the sensor frame, its world pose, its time in seconds);
    // returns the world points found moving, in this scan and in the earlier scans they were
    // matched with (each point once per call).
    std::vector<Eigen::Vector3f> add_scan(const std::vector<Eigen::Vector3f>& points,
                                          const Eigen::Isometry3d& T_world_sensor, double time);
    // Forgets the kept scans (a new session: times restart).
    void clear();

    const MotionStats& stats() const { return stats_; }
    std::size_t memory_bytes() const;

    struct Scan;  // motion_tracker.cpp

  private:
    MotionConfig config_;
    RangeImageConfig image_;
    double max_range_;
    std::deque<std::unique_ptr<Scan>> kept_;
    MotionStats stats_;
};

}  // namespace ltm::maintenance
