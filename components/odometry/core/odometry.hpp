#pragma once
// The LiDAR odometry facade (METHOD.md Algorithm 1): pre-process -> predict -> register against
// the current local map -> check -> update the local maps -> select keyframes. Synchronous, no
// threads of its own, no I/O, no middleware: an adapter feeds scans and publishes the results.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/core/point_cloud.hpp"
#include "odometry/core/keyframe_selector.hpp"
#include "odometry/core/local_map_set.hpp"
#include "odometry/core/motion_model.hpp"
#include "odometry/core/odometry_config.hpp"
#include "registration/core/parallel.hpp"
#include "registration/core/preprocess.hpp"
#include "registration/core/registration.hpp"

namespace ltm::odometry {

enum class FrameStatus {
    kInitialised,          // first usable scan: the first local map starts at the initial pose
    kTracked,              // registered against the local map
    kSkippedTooFewPoints,  // empty or tiny scan: prediction carried forward, map unchanged
    kRejectedStamp,        // stamp not finite or not after the previous one: ignored entirely
    kDiverged,             // registration failed or implausible: prediction carried forward
};
const char* to_string(FrameStatus status);

struct Keyframe {
    std::uint64_t id = 0;
    double stamp = 0.0;  // [s]
    Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();
    std::uint32_t local_map_id = 0;       // map it was registered in
    std::vector<Eigen::Vector3f> points;  // down-sampled (map grid), de-skewed, LiDAR frame
};

struct FrameResult {
    FrameStatus status = FrameStatus::kSkippedTooFewPoints;
    std::string message;  // one line explaining a status other than tracked/initialised
    double stamp = 0.0;
    // The estimate when pose_valid(); otherwise the prediction carried forward (do not publish).
    Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();
    // Of [position (m); rotation vector (rad)], both in odometry axes: R_true = Exp(dr) R.
    registration::Matrix6d covariance = registration::Matrix6d::Identity();
    std::vector<registration::Vector6d>
        degenerate_directions;     // unit, [dt; dr * degeneracy_length]
    double min_information = 0.0;  // of the weakest direction (see RegistrationResult)
    std::size_t input_points = 0;
    std::size_t dropped_non_finite = 0;
    std::size_t dropped_range = 0;
    std::size_t map_points = 0;           // after down-sampling (map grid)
    std::size_t registration_points = 0;  // after down-sampling (registration grid)
    std::size_t correspondences = 0;
    int iterations = 0;         // Gauss-Newton iterations on the fine grid
    int coarse_iterations = 0;  // ... and on the coarse grid (0 without one)
    int attempts = 0;           // registrations run (2: retried from the last pose)
    bool converged = false;
    bool deskewed = false;      // per-point times used to de-skew (at least for the map update)
    double residual_rms = 0.0;  // [m]
    std::uint32_t local_map_id = 0;    // current local map after this frame
    bool new_local_map = false;        // this frame started a local map
    std::optional<Keyframe> keyframe;  // set when this frame is a keyframe
    // Wall time of the stages [ms] (measured, for benchmarks and diagnostics).
    double preprocess_ms = 0.0, registration_ms = 0.0, update_ms = 0.0;

    bool pose_valid() const {
        return status == FrameStatus::kInitialised || status == FrameStatus::kTracked;
    }
    bool degenerate() const { return !degenerate_directions.empty(); }
};

class Odometry {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    explicit Odometry(const OdometryConfig& config, const Eigen::Isometry3d& T_odom_lidar_initial =
                                                        Eigen::Isometry3d::Identity());

    // One scan (LiDAR frame; per-point times, if any, in seconds after cloud.stamp). Never throws
    // on bad data: the status says what happened.
    FrameResult register_frame(const common::PointCloud& cloud);

    const OdometryConfig& config() const { return config_; }
    // The last pose (estimated or carried forward) and whether any frame was accepted yet.
    const Eigen::Isometry3d& pose() const {
        return motion_.poses() ? motion_.last_pose() : initial_pose_;
    }
    bool initialised() const { return !maps_.empty(); }

    // Active local maps, oldest first; the last is the registration target. Empty before the
    // first usable scan.
    const std::deque<LocalMap>& active_local_maps() const { return maps_.active(); }
    // Local maps finished since the last call; the odometry keeps nothing of them. Call it
    // regularly (every frame) to keep memory bounded.
    std::vector<LocalMap> take_finished_local_maps() { return maps_.take_finished(); }
    // End of a run: finish the active maps too (the next scan starts a new first map).
    void finish_local_maps();
    std::size_t memory_bytes() const { return maps_.memory_bytes(); }

  private:
    FrameResult reject(FrameResult result, FrameStatus status, std::string message);
    // Registers the current scan from an initial guess (odometry frame) against the current
    // local map; on success fills the pose, covariance and degeneracy of `r` and returns "",
    // otherwise returns why it failed.
    std::string try_register(const Eigen::Isometry3d& guess, FrameResult* r);
    void accept(const FrameResult& result);

    OdometryConfig config_;
    Eigen::Isometry3d initial_pose_;
    registration::ParallelFor parallel_;
    registration::Preprocessor preprocessor_;
    registration::Registration registration_;
    registration::Registration coarse_registration_;  // used when the maps have a coarse grid
    MotionModel motion_;
    LocalMapSet maps_;
    KeyframeSelector keyframes_;
    std::uint64_t next_keyframe_id_ = 0;
    double typical_rms_ = 0.0;  // running mean of the tracked frames' residual RMS [m]
    bool has_stamp_ = false;
    double last_stamp_ = 0.0;
    registration::PreprocessedScan scan_;  // reused buffers
    std::vector<Eigen::Vector3f> coarse_points_;
};

}  // namespace ltm::odometry
