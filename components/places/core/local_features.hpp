#pragma once
// Local ScanContext++ features for global localisation (METHOD.md section 6): ground points are
// sampled evenly in a cloud, a small ScanContext++ (mean and standard deviation of the heights
// above the sample's ground, per polar bin) is built around each sample. Two clouds' samples are
// matched by local_feature_matching.hpp; the matched positions feed RANSAC over Umeyama
// (registration/core/ransac_alignment.hpp) for the pose.
//
// Both sides are first voxel-down-sampled to the same grid (centroids), so that a dense scan, a
// sparse one and map voxel centres give comparable heights. Ground: the lowest voxel of each cell
// of a 2-D grid, kept where it is not higher than the lowest voxels around it allow for the
// largest ground slope (a car roof, a table top or a wall top is not ground); the samples are the
// points of a lattice of `sample_spacing` (anchored at the frame's origin) whose cell is ground.
// The input frame's z must be up (gravity); the yaw between the two inputs is free.
#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "places/core/scan_context.hpp"

namespace ltm::places {

struct LocalFeatureConfig {
    double voxel_size = 0.6;  // both sides are down-sampled to this grid (centroids) first [m]
    // Ground: a cell of this size is ground when its lowest voxel is at most
    // tan(ground_max_slope_deg) * distance + ground_tolerance above the lowest voxel of every
    // cell within ground_window (that is: no lower ground beside it) [m, deg, m, m].
    double ground_cell = 1.0;
    double ground_max_slope_deg = 15.0;
    double ground_window = 3.0;
    double ground_tolerance = 0.25;
    // Samples on a lattice of this spacing [m]. Denser is better on both sides (more samples in a
    // narrow view; the target lattice quantises the match positions). With RANSAC on the matches,
    // 1.5 m put 46/46 turned KITTI frames within 0.5 m / 2 deg (3 m: 42/46) and 66/86 verified
    // Livox cross-session pairs within 2 m / 5 deg (3 m: 21/86); see local_features_bench.
    double sample_spacing = 1.5;
    double max_range = 40.0;  // samples farther (horizontally) from the origin are not taken [m]
    // At most this many samples, spread evenly when there are more: the points of the 8-spacing
    // sub-lattice first, then of the 4-, the 2-spacing one, the rest (nearest first within each).
    int max_samples = 200;
    // The local descriptor around a sample: points within `radius` (horizontally), at most
    // `max_height` above the sample's ground (higher parts are seen from some places only).
    double radius = 10.0;
    double max_height = 4.0;
    int rings = 8;
    int sectors = 24;
    // Rings of equal area (ring i spans radius * sqrt(i / rings) .. sqrt((i + 1) / rings)) rather
    // than of equal width: the inner bins are not left nearly empty.
    bool equal_area_rings = true;
    int min_points_per_descriptor = 30;  // voxels within the descriptor; fewer: no sample
    int min_occupied_bins = 24;          // occupied bins; fewer: no sample
};

template <class Visitor>
void visit_fields(LocalFeatureConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "voxel_size", c.voxel_size, positive);
    v(prefix + "ground_cell", c.ground_cell, positive);
    v(prefix + "ground_max_slope_deg", c.ground_max_slope_deg, in_range(0, 89));
    v(prefix + "ground_window", c.ground_window, non_negative);
    v(prefix + "ground_tolerance", c.ground_tolerance, non_negative);
    v(prefix + "sample_spacing", c.sample_spacing, positive);
    v(prefix + "max_range", c.max_range, positive);
    v(prefix + "max_samples", c.max_samples, at_least(1));
    v(prefix + "radius", c.radius, positive);
    v(prefix + "max_height", c.max_height, positive);
    v(prefix + "rings", c.rings, in_range(1, 64));
    v(prefix + "sectors", c.sectors, in_range(4, 360));
    v(prefix + "equal_area_rings", c.equal_area_rings, unchecked);
    v(prefix + "min_points_per_descriptor", c.min_points_per_descriptor, at_least(1));
    v(prefix + "min_occupied_bins", c.min_occupied_bins, at_least(1));
}

// The first field that breaks its rule, then the rules across fields; keys relative. nullopt
// when valid.
std::optional<common::ConfigProblem> validate(const LocalFeatureConfig& config);

struct LocalFeatures {
    // Sample points on the ground, in the input frame.
    std::vector<Eigen::Vector3d> positions;
    // One a sample (kind kMeanVariance), centred at the sample, z relative to its ground height.
    std::vector<places::ScanContext> descriptors;
    // The lattice spacing of the samples (positions are multiples of it in x and y) [m].
    double sample_spacing = 0.0;

    std::size_t size() const { return positions.size(); }
    bool empty() const { return positions.empty(); }
};

// The features of a cloud (a scan, or map voxel centres) in a frame whose z is up; samples
// within config.max_range of the origin. Non-finite points are skipped. Throws
// common::ConfigError on an invalid config.
LocalFeatures make_local_features(const std::vector<Eigen::Vector3f>& points,
                                  const LocalFeatureConfig& config);

// The same, but the samples are those within `sample_radius` (horizontally) of `centre` (the
// map side: a region around a keyframe); `points` may extend much farther (only those within
// sample_radius + radius of the centre are used). config.max_range is not used.
LocalFeatures make_local_features(const std::vector<Eigen::Vector3f>& points,
                                  const LocalFeatureConfig& config, const Eigen::Vector3d& centre,
                                  double sample_radius);

}  // namespace ltm::places
