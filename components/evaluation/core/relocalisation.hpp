#pragma once
// Relocalisation (kidnapped robot / session start) success against ground truth.
// An attempt succeeds when it returned a pose whose translation error is at most
// max_translation and whose rotation error is at most max_rotation_deg. The success rate is over
// all attempts; a returned pose outside the tolerances is a wrong relocalisation (worse than none
// for a robot, so counted apart).
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "evaluation/core/stats.hpp"

namespace ltm::eval {

struct RelocAttempt {
    std::size_t frame = 0;                                   // index into the reference poses
    double time_s = 0.0;                                     // time the attempt took [s]
    bool has_pose = false;                                   // false: the system gave up
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // estimated T_world_sensor
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

using RelocAttempts = std::vector<RelocAttempt, Eigen::aligned_allocator<RelocAttempt>>;

struct RelocConfig {
    double max_translation = 0.5;   // [m]
    double max_rotation_deg = 5.0;  // [deg]
};

struct RelocResult {
    std::size_t attempts = 0, successes = 0;
    std::size_t wrong = 0;          // returned a pose outside the tolerances
    std::size_t no_pose = 0;        // returned nothing
    std::size_t out_of_range = 0;   // attempts naming a frame with no reference (not counted)
    double success_rate = 0.0;      // successes / attempts [0, 1]
    ErrorStats time_all_s;          // [s] over all attempts
    ErrorStats time_success_s;      // [s] over successful attempts
    ErrorStats translation_error;   // [m] over successful attempts
    ErrorStats rotation_error_deg;  // [deg] over successful attempts
};

RelocResult evaluate_relocalisation(const RelocAttempts& attempts,
                                    const common::PoseList& reference,
                                    const RelocConfig& config = {});

}  // namespace ltm::eval
