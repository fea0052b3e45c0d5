#pragma once
// Geometric verification of a loop candidate (METHOD.md section 3): the keyframe is registered
// against the candidate's local map with the registration core (IMLS point-to-surface
// Gauss-Newton), first with a wide reach from an initial guess (the graph's estimate within a
// session, the descriptor's guess), then with the odometry's fine settings; accepted with enough
// inliers (points whose IMLS distance is small at the final pose), a large enough inlier fraction
// and a small inlier RMS.
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "common/core/local_map_data.hpp"
#include "registration/core/preprocess.hpp"
#include "registration/core/registration_config.hpp"
#include "registration/core/registration_target.hpp"
#include "registration/core/se3.hpp"

namespace ltm::registration {

struct LoopVerifierConfig {
    // First pass, from the guess: on a coarse grid of coarse_factor voxels fitted to the map's
    // surfaces (0: on the fine grid with the coarse settings).
    int coarse_factor = 3;
    registration::RegistrationConfig coarse = coarse_defaults();
    registration::RegistrationConfig fine = fine_defaults();  // second pass: must converge
    double min_planarity = 0.4;  // map voxels below this planarity are not used
    double downsample = 1.0;     // grid for the keyframe's points [m] (0: keep all)
    int max_points = 6000;       // cap on the registered points (evenly thinned)
    // Initial yaws tried about the descriptor's yaw [deg]; the best-scoring result is kept.
    std::vector<double> yaw_offsets = {0.0};
    double inlier_distance = 0.3;  // |IMLS distance| below this: an inlier [m]
    int min_inliers = 400;
    double min_inlier_fraction = 0.5;  // of the registered points
    double max_inlier_rms = 0.15;      // [m]
    // Of the points on structure (surfaces that are not ground-like) within reach of a surface,
    // this share must be inliers: a wrong alignment still fits the ground, not the walls.
    double min_structure_inlier_ratio = 0.75;
    int min_structure_points = 100;
    // At most this share of the registered points may have no map surface within reach at the
    // final pose (1: no limit). The structure ratio above counts only points that reach a
    // surface: a wrong alignment that fits a wall or a row of posts well and leaves a fifth of
    // the scan in the map's empty space passes it (site_loop, another day's scans turned, on the
    // 1-lap map: 58.8 m / 180 deg and 3.45 m along the road with 19-24 % of the points reaching
    // no surface, structure ratios 0.86-0.96; at the true poses 1-1.5 %).
    double max_unmatched_fraction = 1.0;
    // Refuse a registration with a degenerate direction (along a straight road or a corridor the
    // result stays at the guess in that direction, which is the matched keyframe's place, not the
    // query's).
    bool refuse_degenerate = true;
    // The result may move this far from the guess (a revisit is a few metres from the matched
    // keyframe; a registration that slides farther has found another place) [m], [deg].
    double max_correction_translation = 8.0;
    double max_correction_rotation = 30.0;
    int cache_size = 6;  // rebuilt local maps kept
    // How much of the keyframe the map explains, direction by direction: the keyframe's points are
    // split into this many azimuth sectors about the sensor (the first centred on its x axis) and
    // each sector holding at least min_sector_share of them gets its own inlier fraction
    // (LoopVerification::min_sector_fraction). Reported, not judged here: a caller (the mapping,
    // against a loaded map's edge) decides.
    int sectors = 4;
    double min_sector_share = 0.1;

    static registration::RegistrationConfig fine_defaults() {
        registration::RegistrationConfig c;  // the odometry's, with more iterations
        c.max_iterations = 50;
        return c;
    }
    static registration::RegistrationConfig coarse_defaults() {
        registration::RegistrationConfig c;  // distances for 3 m coarse voxels
        c.max_correspondence_distance = 4.5;
        c.min_normal_agreement = 0.5;
        c.kernel_scale = 0.3;
        c.max_iterations = 40;
        c.convergence_translation = 3e-3;
        c.convergence_rotation = 3e-2;
        c.stability_weighting = false;
        return c;
    }
};

// Calls v(key, field, rule) for every field, keys under `prefix` ("verification."); the rule is the
// field's (common/core/config_check.hpp). An infinite limit is no limit.
template <class Visitor>
void visit_fields(LoopVerifierConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "coarse_factor", c.coarse_factor, zero_or_in(2, 16));
    registration::visit_fields(c.coarse, prefix + "coarse.", v);
    registration::visit_fields(c.fine, prefix + "fine.", v);
    v(prefix + "min_planarity", c.min_planarity, unchecked);
    v(prefix + "downsample", c.downsample, non_negative.or_infinite());
    v(prefix + "max_points", c.max_points, at_least(100));
    v(prefix + "yaw_offsets", c.yaw_offsets, not_empty);
    v(prefix + "inlier_distance", c.inlier_distance, positive.or_infinite());
    v(prefix + "min_inliers", c.min_inliers, at_least(1));
    v(prefix + "min_inlier_fraction", c.min_inlier_fraction, unit);
    v(prefix + "max_inlier_rms", c.max_inlier_rms, positive.or_infinite());
    v(prefix + "min_structure_inlier_ratio", c.min_structure_inlier_ratio, unit);
    v(prefix + "min_structure_points", c.min_structure_points, non_negative);
    v(prefix + "max_unmatched_fraction", c.max_unmatched_fraction, unit);
    v(prefix + "refuse_degenerate", c.refuse_degenerate, unchecked);
    v(prefix + "max_correction_translation", c.max_correction_translation, positive.or_infinite());
    v(prefix + "max_correction_rotation", c.max_correction_rotation, positive.or_infinite());
    v(prefix + "cache_size", c.cache_size, at_least(1));
    v(prefix + "sectors", c.sectors, in_range(1, 36));
    v(prefix + "min_sector_share", c.min_sector_share, unit);
}

// The first field that breaks its rule (key relative: "min_inliers"); nullopt when valid.
std::optional<common::ConfigProblem> validate(const LoopVerifierConfig& config);

struct LoopVerification {
    bool accepted = false;
    std::string reason;  // why it was refused (one line), empty when accepted
    Eigen::Isometry3d T_anchor_lidar = Eigen::Isometry3d::Identity();  // in the candidate anchor
    std::size_t points = 0, inliers = 0;
    double inlier_fraction = 0.0;
    double inlier_rms = 0.0;                // [m]
    double correction_translation = 0.0;    // result vs guess [m]
    double correction_rotation = 0.0;       // [deg]
    std::size_t degenerate_directions = 0;  // of the fine registration
    // The fine registration's Hessian (sum w J^T J) and covariance at the final pose, in the grid
    // frame ([dt; dr], as RegistrationResult): what a caller needs about the fit's constraints
    // without registering again.
    Matrix6d hessian = Matrix6d::Zero();
    Matrix6d covariance = Matrix6d::Identity();
    // Points on structure (the normal of their surface not vertical, in the grid frame) that have
    // a surface within reach, and those of them that are inliers.
    std::size_t structure_points = 0, structure_inliers = 0;
    // The lowest inlier fraction over the azimuth sectors holding at least min_sector_share of
    // the points (1 when none does), and that sector's centre (LiDAR frame, deg from x towards
    // y): a keyframe at a map's edge is explained on one side and not towards the edge.
    double min_sector_fraction = 1.0;
    double weakest_sector_deg = 0.0;
    // Points with no map surface within reach at the final pose (in the map's empty space, or
    // beyond its extent).
    std::size_t unmatched = 0;
    int iterations = 0;     // coarse + fine
    std::size_t guess = 0;  // index of the initial guess the result came from
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

using GuessList = std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>;

class LoopVerifier {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    explicit LoopVerifier(const LoopVerifierConfig& config);

    const LoopVerifierConfig& config() const { return config_; }

    // points: the keyframe in its LiDAR frame; map: the candidate local map, known to the cache
    // as `map_key` (the same key must mean the same content); guess: the keyframe's pose in the
    // candidate map's anchor frame. Never throws on bad data: the result says why it failed.
    LoopVerification verify(const std::vector<Eigen::Vector3f>& points, std::uint64_t map_key,
                            const common::LocalMapData& map, const Eigen::Isometry3d& guess);
    // The same from several initial guesses, tried in order (each with the yaw offsets) until
    // one is accepted; otherwise the best refused result. A registration's basin is a few
    // metres: a guess close to the truth (the graph's estimate of a revisit within a session)
    // succeeds where a descriptor's guess at the matched keyframe's place ends in a wrong
    // minimum.
    LoopVerification verify(const std::vector<Eigen::Vector3f>& points, std::uint64_t map_key,
                            const common::LocalMapData& map, const GuessList& guesses);
    // The same against a target the caller prepared and keeps (global localisation registers
    // against one merged map). kFineOnly: the guesses are in the fine pass's basin already (a
    // caller's own coarse probe put them there): the coarse pass is left out.
    enum class Passes { kCoarseThenFine, kFineOnly };
    LoopVerification verify(const std::vector<Eigen::Vector3f>& points,
                            const RegistrationTarget& target, const GuessList& guesses,
                            Passes passes = Passes::kCoarseThenFine);

    // The cached targets' grids (bytes).
    std::size_t memory_bytes() const;
    // Drops the cached target of `map_key` (its map left memory: paged out).
    void forget(std::uint64_t map_key);

  private:
    struct Cached {
        std::uint64_t key;
        std::shared_ptr<RegistrationTarget> target;
    };
    std::shared_ptr<RegistrationTarget> target(std::uint64_t key, const common::LocalMapData& map);
    LoopVerification attempt(const std::vector<Eigen::Vector3f>& points,
                             const RegistrationTarget& target, const Eigen::Isometry3d& guess,
                             Passes passes);

    LoopVerifierConfig config_;
    std::deque<Cached> cache_;  // most recent first
    registration::VoxelDownsampler sampler_;
    std::vector<Eigen::Vector3f> sampled_;
};

}  // namespace ltm::registration
