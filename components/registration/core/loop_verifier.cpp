#include "registration/core/loop_verifier.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "registration/core/imls.hpp"
#include "registration/core/registration.hpp"
#include "registration/core/sector_overlap.hpp"

namespace ltm::registration {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

const LoopVerifierConfig& checked(const LoopVerifierConfig& c) {
    common::throw_if(validate(c), "verification");
    return c;
}

Eigen::Isometry3d yawed(const Eigen::Isometry3d& T, double yaw) {
    Eigen::Isometry3d out = T;
    out.linear() = T.linear() * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return out;
}

}  // namespace

std::optional<common::ConfigProblem> validate(const LoopVerifierConfig& config) {
    LoopVerifierConfig c =
        config;  // visit_fields takes a mutable config (loaders write through it)
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

LoopVerifier::LoopVerifier(const LoopVerifierConfig& config) : config_(checked(config)) {}

void LoopVerifier::forget(std::uint64_t map_key) {
    cache_.erase(std::remove_if(cache_.begin(), cache_.end(),
                                [&](const Cached& c) { return c.key == map_key; }),
                 cache_.end());
}

std::size_t LoopVerifier::memory_bytes() const {
    std::size_t n = sampled_.capacity() * sizeof(Eigen::Vector3f);
    for (const Cached& c : cache_) n += c.target->memory_bytes();
    return n;
}

std::shared_ptr<RegistrationTarget> LoopVerifier::target(std::uint64_t key,
                                                         const common::LocalMapData& map) {
    for (auto it = cache_.begin(); it != cache_.end(); ++it) {
        if (it->key != key) continue;
        Cached hit = *it;
        cache_.erase(it);
        cache_.push_front(hit);
        return hit.target;
    }
    auto t = std::make_shared<RegistrationTarget>(
        make_registration_target(map, config_.min_planarity, config_.coarse_factor));
    cache_.push_front({key, t});
    while (cache_.size() > std::size_t(config_.cache_size)) cache_.pop_back();
    return t;
}

LoopVerification LoopVerifier::attempt(const std::vector<Eigen::Vector3f>& points,
                                       const RegistrationTarget& t, const Eigen::Isometry3d& guess,
                                       Passes passes) {
    LoopVerification v;
    v.points = points.size();
    registration::Registration fine(config_.fine, t.fine.voxel_size());
    Eigen::Isometry3d start = t.T_anchor_grid.inverse() * guess;
    if (passes == Passes::kCoarseThenFine) {
        const registration::VoxelGrid& first = t.coarse ? *t.coarse : t.fine;
        registration::Registration coarse(config_.coarse, first.voxel_size());
        const registration::RegistrationResult c = coarse.align(points, first, start);
        v.iterations = c.iterations;
        if (!c.ok()) {
            v.reason = std::string("coarse registration: ") + registration::to_string(c.status) +
                       " (" + std::to_string(c.correspondences) + " correspondences)";
            return v;
        }
        start = c.T_map_lidar;
    }
    const registration::RegistrationResult f = fine.align(points, t.fine, start);
    v.iterations += f.iterations;
    if (f.status != registration::RegistrationResult::Status::kConverged ||
        !f.T_map_lidar.matrix().allFinite()) {
        v.reason = std::string("fine registration: ") + registration::to_string(f.status) + " (" +
                   std::to_string(f.correspondences) + " correspondences)";
        return v;
    }
    // Inliers at the final pose, with the fine IMLS settings.
    const registration::ImlsParams imls = fine.imls_params();
    const Eigen::Matrix3f R = f.T_map_lidar.linear().cast<float>();
    const Eigen::Vector3f tr = f.T_map_lidar.translation().cast<float>();
    double sq = 0.0;
    registration::ImlsResult r;
    SectorCounter sectors(config_.sectors);
    for (const Eigen::Vector3f& p : points) {
        if (!registration::imls_distance(t.fine, R * p + tr, imls, &r)) {
            sectors.add(p, false);
            ++v.unmatched;
            continue;
        }
        const bool inlier = std::abs(r.distance) <= config_.inlier_distance;
        sectors.add(p, inlier);
        // Structure: not ground-like (the ground matches almost anywhere).
        if (std::abs(r.normal.z()) < 0.8f) {
            ++v.structure_points;
            v.structure_inliers += inlier;
        }
        if (!inlier) continue;
        ++v.inliers;
        sq += double(r.distance) * r.distance;
    }
    v.inlier_fraction = v.points ? double(v.inliers) / double(v.points) : 0.0;
    v.inlier_rms = v.inliers ? std::sqrt(sq / double(v.inliers)) : 0.0;
    const SectorOverlap weakest = sectors.weakest(config_.min_sector_share);
    v.min_sector_fraction = weakest.min_fraction;
    v.weakest_sector_deg = weakest.weakest_deg;
    v.T_anchor_lidar = t.T_anchor_grid * f.T_map_lidar;
    const Eigen::Isometry3d correction = guess.inverse() * v.T_anchor_lidar;
    v.correction_translation = correction.translation().norm();
    v.correction_rotation = Eigen::AngleAxisd(correction.linear()).angle() / kDegToRad;
    v.degenerate_directions = f.degenerate_directions.size();
    v.hessian = f.hessian;
    v.covariance = f.covariance;
    std::ostringstream why;
    if (config_.refuse_degenerate && v.degenerate_directions > 0) {
        why << "registration is degenerate in " << v.degenerate_directions << " direction(s)";
        why.precision(2);
        for (const registration::Vector6d& d : f.degenerate_directions)
            why << " [" << d.transpose() << "]";
    } else if (v.correction_translation > config_.max_correction_translation ||
               v.correction_rotation > config_.max_correction_rotation) {
        why << "moved " << v.correction_translation << " m / " << v.correction_rotation
            << " deg from the guess (limits " << config_.max_correction_translation << " m / "
            << config_.max_correction_rotation << " deg)";
    } else if (v.structure_points < std::size_t(config_.min_structure_points)) {
        why << v.structure_points << " points on structure, fewer than "
            << config_.min_structure_points;
    } else if (double(v.structure_inliers) <
               config_.min_structure_inlier_ratio * double(v.structure_points)) {
        why << "structure inlier ratio " << double(v.structure_inliers) / double(v.structure_points)
            << " below " << config_.min_structure_inlier_ratio;
    } else if (double(v.unmatched) > config_.max_unmatched_fraction * double(v.points)) {
        why << "unmatched fraction " << double(v.unmatched) / double(v.points) << " above "
            << config_.max_unmatched_fraction << " (points with no map surface within reach)";
    } else if (v.inliers < std::size_t(config_.min_inliers)) {
        why << v.inliers << " inliers, fewer than " << config_.min_inliers;
    } else if (v.inlier_fraction < config_.min_inlier_fraction) {
        why << "inlier fraction " << v.inlier_fraction << " below " << config_.min_inlier_fraction;
    } else if (v.inlier_rms > config_.max_inlier_rms) {
        why << "inlier RMS " << v.inlier_rms << " m above " << config_.max_inlier_rms << " m";
    }
    v.reason = why.str();
    v.accepted = v.reason.empty();
    return v;
}

LoopVerification LoopVerifier::verify(const std::vector<Eigen::Vector3f>& points,
                                      std::uint64_t map_key, const common::LocalMapData& map,
                                      const Eigen::Isometry3d& guess) {
    return verify(points, map_key, map, GuessList{guess});
}

LoopVerification LoopVerifier::verify(const std::vector<Eigen::Vector3f>& points,
                                      std::uint64_t map_key, const common::LocalMapData& map,
                                      const GuessList& guesses) {
    LoopVerification best;
    if (map.voxels.empty() || !(map.voxel_size > 0.0f)) {
        best.reason = "candidate local map has no voxels";
        return best;
    }
    return verify(points, *target(map_key, map), guesses);
}

LoopVerification LoopVerifier::verify(const std::vector<Eigen::Vector3f>& points,
                                      const RegistrationTarget& target, const GuessList& guesses,
                                      Passes passes) {
    LoopVerification best;
    if (guesses.empty()) {
        best.reason = "no initial guess";
        return best;
    }
    for (const Eigen::Isometry3d& guess : guesses) {
        if (!guess.matrix().allFinite()) {
            best.reason = "initial guess is not finite";
            return best;
        }
    }
    sampler_.sample(points, config_.downsample, std::size_t(config_.max_points), &sampled_);
    if (sampled_.size() < std::size_t(config_.min_inliers)) {
        best.reason = "keyframe has " + std::to_string(sampled_.size()) +
                      " points after down-sampling, fewer than min_inliers";
        best.points = sampled_.size();
        return best;
    }
    const RegistrationTarget* t = &target;
    if (t->fine.usable_voxels() == 0) {
        best.reason = "candidate local map has no usable voxel";
        return best;
    }
    bool first = true;
    for (std::size_t g = 0; g < guesses.size() && !best.accepted; ++g) {
        for (const double offset : config_.yaw_offsets) {
            LoopVerification v =
                attempt(sampled_, *t, yawed(guesses[g], offset * kDegToRad), passes);
            v.guess = g;
            const bool better = v.accepted != best.accepted ? v.accepted : v.inliers > best.inliers;
            if (first || better) best = v;
            first = false;
            if (best.accepted && best.inlier_fraction > 0.8) break;  // no better start
        }
    }
    return best;
}

}  // namespace ltm::registration
