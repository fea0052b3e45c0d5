#pragma once
// One day of a lifelong run scored against the truth: the map-frame poses published online, put
// in the world by ONE rigid alignment (fitted once, on day 0's final SLAM keyframes, and used for
// every day: the same place must get the same coordinates every day), and the time from each
// kidnap to the first correct pose.
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "evaluation/core/ate.hpp"

namespace ltm::eval {

// T_world_map from `keyframes` (map frame) matched by stamp (within max_dt) to `truth` (world):
// compute_ate_detail's Umeyama SE(3), no scale. `ate` is the keyframes' fit; `matched` how many.
struct MapAlignment {
    Eigen::Isometry3d T_world_map = Eigen::Isometry3d::Identity();
    AteResult ate;
    std::size_t matched = 0, unmatched = 0;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};
MapAlignment fit_map_alignment(const common::Trajectory& keyframes, const common::Trajectory& truth,
                               double max_dt = 0.02);

// The same alignment with one scale fitted too (Umeyama with scale): a diagnostic, not the
// benchmark's alignment. A map's scale is what no loop observes (an odometry that measures
// distances a little short makes a map that closes every loop and is uniformly small); scoring a
// day in this alignment tells that scale from the error loops and ties can remove. World
// positions are T_world_map * (scale * p_map).
struct MapSimilarity {
    Eigen::Isometry3d T_world_map = Eigen::Isometry3d::Identity();
    double scale = 1.0;  // world metres per map metre
    double rmse = 0.0;   // [m] the keyframes in this fit
    std::size_t matched = 0;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};
MapSimilarity fit_map_similarity(const common::Trajectory& keyframes,
                                 const common::Trajectory& truth, double max_dt = 0.02);
// The poses with their positions multiplied by `scale` (about the map frame's origin), so that
// score_day_poses(scaled_positions(poses, s.scale), truth, s.T_world_map, ...) scores them in s.
common::Trajectory scaled_positions(const common::Trajectory& poses, double scale);

struct DayPoseConfig {
    double max_dt = 0.02;  // [s] a published pose belongs to the scan with this stamp
    double wrong = 0.5;    // [m] a pose farther than this from the truth is wrong
};

struct KidnapRecovery {
    double stamp = 0.0;      // first scan after the kidnap [s]
    bool recovered = false;  // a correct pose before the session ended
    double time_s = 0.0;     // scan time from the kidnap to the first correct pose [s]
    std::size_t scans = 0;   // scans from the kidnap to it (0: the kidnap's own scan)
    std::size_t wrong = 0;   // wrong poses published before it
};

struct DayPoseScore {
    std::size_t scans = 0;                    // truth scans of the day
    std::size_t with_pose = 0;                // scans with a published map pose
    std::size_t wrong = 0;                    // of those, farther than `wrong` from the truth
    double rmse = 0.0, p95 = 0.0, max = 0.0;  // [m] position errors of the scans with a pose
    std::vector<KidnapRecovery> kidnaps;
    // Per truth scan (truth order): error [m], negative without a pose; the pose in the world.
    std::vector<double> error;
    common::PoseList aligned;  // identity where there is no pose
};

// `map_poses` in the map frame, `truth` = every scan of the day in the world frame (stamps as
// the scans'), `kidnap_stamps` the first scans after each kidnap (and the start when the robot
// was not told it). A pose is paired with the truth scan of the nearest stamp within max_dt.
DayPoseScore score_day_poses(const common::Trajectory& map_poses, const common::Trajectory& truth,
                             const Eigen::Isometry3d& T_world_map,
                             const std::vector<double>& kidnap_stamps,
                             const DayPoseConfig& config = {});

}  // namespace ltm::eval
