#pragma once
// Rigid alignment from putative point correspondences with outliers (METHOD.md section 6: the
// initial pose of global localisation, "SVD (Kabsch/Umeyama) inside RANSAC"): minimal samples of
// three correspondences, Umeyama's closed form on each (Eigen::umeyama, no scaling), the
// hypothesis with the most correspondences within `inlier_distance`, refitted on all of its
// inliers. Deterministic for a given seed. No answer when too few correspondences agree: a
// confident wrong pose is the failure global localisation must not make.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"

namespace ltm::registration {

struct RansacAlignmentConfig {
    int iterations = 2000;         // minimal samples tried (fewer when the answer is certain)
    double inlier_distance = 0.5;  // |T * source - target| below this: an inlier [m]
    int min_inliers = 8;           // fewer agreeing correspondences: no answer
    // Sample triangles whose shortest side is under this are skipped (degenerate: a line) [m].
    double min_sample_spread = 1.0;
    double confidence = 0.999;  // stop when a better hypothesis is this unlikely to exist
    int seed = 1;               // of the sample draws (the same seed, the same answer)
};

template <class Visitor>
void visit_fields(RansacAlignmentConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "iterations", c.iterations, at_least(1));
    v(prefix + "inlier_distance", c.inlier_distance, positive);
    v(prefix + "min_inliers", c.min_inliers, at_least(3));
    v(prefix + "min_sample_spread", c.min_sample_spread, non_negative);
    v(prefix + "confidence", c.confidence, in_range(0, 1));
    v(prefix + "seed", c.seed, non_negative);
}

std::optional<common::ConfigProblem> validate(const RansacAlignmentConfig& config);

struct RansacAlignment {
    Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
    std::vector<std::size_t> inliers;  // indices into the correspondences
    double inlier_rms = 0.0;           // [m]
    int iterations = 0;                // samples drawn
};

// Correspondences source[i] <-> target[i] (equal sizes). nullopt when fewer than
// config.min_inliers agree on one rigid motion (or fewer than 3 correspondences).
std::optional<RansacAlignment> ransac_align(const std::vector<Eigen::Vector3d>& source,
                                            const std::vector<Eigen::Vector3d>& target,
                                            const RansacAlignmentConfig& config = {});

}  // namespace ltm::registration
