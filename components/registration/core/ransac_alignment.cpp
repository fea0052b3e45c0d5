#include "registration/core/ransac_alignment.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace ltm::registration {
namespace {

// Rigid (no scale) least-squares fit of the listed correspondences.
Eigen::Isometry3d fit(const std::vector<Eigen::Vector3d>& source,
                      const std::vector<Eigen::Vector3d>& target,
                      const std::vector<std::size_t>& which) {
    Eigen::Matrix3Xd s(3, which.size()), t(3, which.size());
    for (std::size_t k = 0; k < which.size(); ++k) {
        s.col(Eigen::Index(k)) = source[which[k]];
        t.col(Eigen::Index(k)) = target[which[k]];
    }
    Eigen::Isometry3d T;
    T.matrix() = Eigen::umeyama(s, t, false);
    return T;
}

void collect_inliers(const std::vector<Eigen::Vector3d>& source,
                     const std::vector<Eigen::Vector3d>& target, const Eigen::Isometry3d& T,
                     double threshold, std::vector<std::size_t>* inliers, double* sq_sum) {
    inliers->clear();
    *sq_sum = 0.0;
    const double t2 = threshold * threshold;
    for (std::size_t i = 0; i < source.size(); ++i) {
        const double d2 = (T * source[i] - target[i]).squaredNorm();
        if (d2 < t2) {
            inliers->push_back(i);
            *sq_sum += d2;
        }
    }
}

}  // namespace

std::optional<common::ConfigProblem> validate(const RansacAlignmentConfig& config) {
    RansacAlignmentConfig c = config;
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

std::optional<RansacAlignment> ransac_align(const std::vector<Eigen::Vector3d>& source,
                                            const std::vector<Eigen::Vector3d>& target,
                                            const RansacAlignmentConfig& config) {
    const std::size_t n = std::min(source.size(), target.size());
    if (n < 3 || source.size() != target.size()) return std::nullopt;
    std::mt19937 rng(std::uint32_t(config.seed));
    std::uniform_int_distribution<std::size_t> pick(0, n - 1);
    const double spread2 = config.min_sample_spread * config.min_sample_spread;
    RansacAlignment best;
    std::vector<std::size_t> inliers;
    double best_sq = 0.0, sq = 0.0;
    int needed = config.iterations;
    for (int it = 0; it < needed; ++it) {
        best.iterations = it + 1;
        const std::size_t a = pick(rng), b = pick(rng), c = pick(rng);
        if (a == b || b == c || a == c) continue;
        // Both triangles must be spread (not a line or a point) and agree in shape: a rigid
        // motion keeps every side's length.
        bool usable = true;
        for (const auto& [i, j] : {std::pair{a, b}, std::pair{b, c}, std::pair{a, c}}) {
            const double ds = (source[i] - source[j]).squaredNorm();
            const double dt = (target[i] - target[j]).squaredNorm();
            if (ds < spread2 || dt < spread2 ||
                std::abs(std::sqrt(ds) - std::sqrt(dt)) > 2.0 * config.inlier_distance) {
                usable = false;
            }
        }
        if (!usable) continue;
        const Eigen::Isometry3d T = fit(source, target, {a, b, c});
        if (!T.matrix().allFinite()) continue;
        collect_inliers(source, target, T, config.inlier_distance, &inliers, &sq);
        if (inliers.size() > best.inliers.size() ||
            (inliers.size() == best.inliers.size() && sq < best_sq)) {
            best.inliers = inliers;
            best.T_target_source = T;
            best_sq = sq;
            // Samples needed to draw an all-inlier triple with the given confidence.
            const double w = double(inliers.size()) / double(n);
            const double p_good = w * w * w;
            if (p_good >= 1.0) {
                needed = std::min(needed, it + 1);
            } else if (p_good > 0.0) {
                const double k = std::log(1.0 - config.confidence) / std::log(1.0 - p_good);
                needed = std::min(needed, int(std::ceil(k)) + 1);
            }
        }
    }
    if (best.inliers.size() < std::size_t(std::max(3, config.min_inliers))) return std::nullopt;
    // Refit on every inlier, then once more on the inliers of the refit.
    for (int round = 0; round < 2; ++round) {
        const Eigen::Isometry3d T = fit(source, target, best.inliers);
        collect_inliers(source, target, T, config.inlier_distance, &inliers, &sq);
        if (inliers.size() < best.inliers.size()) break;
        best.T_target_source = T;
        best.inliers = inliers;
        best_sq = sq;
    }
    best.inlier_rms = std::sqrt(best_sq / double(best.inliers.size()));
    return best;
}

}  // namespace ltm::registration
