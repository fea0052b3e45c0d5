#pragma once
// Segments of a region's non-ground voxels by Euclidean clustering of their centres (PCL's
// EuclideanClusterExtraction over a k-d tree). PCL is kept in segmentation.cpp alone: its headers
// are slow to compile.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "maintenance/core/maintenance_config.hpp"

namespace ltm::maintenance {

// Labels 1..N (0: in a cluster smaller than min_voxels) for the given points, and N.
struct Segmentation {
    std::vector<std::uint32_t> label;
    std::uint32_t segments = 0;
};

Segmentation euclidean_segments(const SegmentationConfig& config,
                                const std::vector<Eigen::Vector3f>& points);

}  // namespace ltm::maintenance
