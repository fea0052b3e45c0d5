#pragma once
// Matching local features (METHOD.md section 6): each query sample's best target samples by the
// distance of their local ScanContext++ descriptors (2-Wasserstein of two 1-D Gaussians a bin,
// minimised over sector shifts: the shift is the yaw between the clouds), after a yaw-invariant
// ring-key pre-filter. The samples come from local_features.hpp; the matched positions feed RANSAC
// over Umeyama (registration/core/ransac_alignment.hpp).
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "places/core/local_features.hpp"
#include "places/core/scan_context.hpp"

namespace ltm::places {

struct LocalFeatureMatchConfig {
    // Distance of two descriptors at a shift: the mean over the bins occupied in either of
    //   both occupied:        min((mean_q - mean_t)^2 + (std_q - std_t)^2, empty_bin_cost),
    //   query only occupied:  empty_bin_cost (the query sees something the target does not),
    //   target only occupied: unseen_bin_cost (the query may not have seen it: a partial view).
    double empty_bin_cost = 1.0;   // [m^2]
    double unseen_bin_cost = 0.5;  // [m^2]
    // Pre-filter: per query, only the targets with the nearest ring keys (yaw-invariant: per
    // ring, the mean height and the mean spread of its occupied bins) are compared in full.
    int key_candidates = 40;
    int per_query = 3;                                              // best targets kept a query
    double max_distance = std::numeric_limits<double>::infinity();  // farther: dropped [m^2]
    // The 2nd..per_query-th best of a query are kept only within ratio * the best's distance.
    double ratio = std::numeric_limits<double>::infinity();
    bool mutual = false;  // keep only matches whose target's best query is this query
};

template <class Visitor>
void visit_fields(LocalFeatureMatchConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "empty_bin_cost", c.empty_bin_cost, positive);
    v(prefix + "unseen_bin_cost", c.unseen_bin_cost, non_negative);
    v(prefix + "key_candidates", c.key_candidates, at_least(1));
    v(prefix + "per_query", c.per_query, at_least(1));
    v(prefix + "max_distance", c.max_distance, positive.or_infinite());
    v(prefix + "ratio", c.ratio, at_least(1).or_infinite());
    v(prefix + "mutual", c.mutual, unchecked);
}

std::optional<common::ConfigProblem> validate(const LocalFeatureMatchConfig& config);

struct FeatureMatch {
    std::size_t query = 0, target = 0;  // sample indices
    double distance = 0.0;              // descriptor distance at the best shift [m^2]
    // Rotation of the query frame relative to the target's about z (R_target_query = Rz(yaw)),
    // from the best sector shift refined by a parabola through its neighbours [rad], (-pi, pi].
    double yaw = 0.0;
    // The target sample's position moved toward the query sample's true place: per lattice axis,
    // a parabola through the distances of the query to the target sample and to its two lattice
    // neighbours (at the best shift), when both neighbours are samples too (else unmoved); at
    // most half a spacing an axis. This undoes most of the lattice quantisation.
    Eigen::Vector3d target_position = Eigen::Vector3d::Zero();
};

// For every query sample its best `per_query` target samples (min over sector shifts), filtered
// as the config says, all sorted by distance. Descriptors of another shape than the first
// query's are not matched. Throws common::ConfigError on an invalid config.
std::vector<FeatureMatch> match_local_features(const LocalFeatures& query,
                                               const LocalFeatures& target,
                                               const LocalFeatureMatchConfig& config);

// The 2 * rings ring key used by the pre-filter (zeros for an empty descriptor).
Eigen::VectorXf local_ring_key(const places::ScanContext& descriptor);

}  // namespace ltm::places
