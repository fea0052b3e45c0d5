#pragma once
// Objects that move within a short window, found scan against scan (issue 26 item 5): what the
// voxels' view histories cannot tell in a second. A walker moving 1 m in 1 s keeps being hit in
// the voxels it spans; no view sees through them, and a motorcyclist joined to the road's
// segment cannot leave with its segment. Positive evidence instead: the same shape, displaced.
//
// Per scan (world frame): its points in cells of `cell`; the ground (cells within ground_height
// of the lowest cell of their 3 x 3 column neighbourhood); the other cells clustered (cells
// within `neighbourhood` cells of each other); clusters of object size (min_cells..max_cells,
// at most max_extent wide and max_height tall) are followed. Each is compared with every kept
// scan min_lag..max_lag s earlier: it is moving when
//   - a cluster of that scan within max_speed x lag matches it rigidly displaced by at least
//     min_shift (after a few nearest-cell iterations from the centroids' difference, at least
//     min_match of the cells of each matched within match_distance of the other's), and
//   - its place now was empty then, and the earlier cluster's place is empty now: of the cells
//     the other scan saw (occupied within a cell, or seen through by its beams: its range image),
//     at least min_known, at most max_overlap occupied.
// A parked car seen from a passing car changes its visible side, not its place: its cells are
// occupied (or occluded) in the other scan, never empty. Each cluster is also linked to the
// cluster of the previous scan that matches it rigidly (any displacement): the same object, so
// an object found moving is moving in the scans between and after (the middle of a 1 m walk is
// less than its width from either end). The clusters' points are returned as moving; the caller
// flags their voxels (LongTermMap).
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
