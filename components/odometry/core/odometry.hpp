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
#include "odometry/core/heading_skill.hpp"
#include "odometry/core/keyframe_selector.hpp"
#include "odometry/core/local_map_set.hpp"
#include "odometry/core/motion_model.hpp"
#include "odometry/core/motion_prior.hpp"
#include "odometry/core/observability.hpp"
#include "odometry/core/odometry_config.hpp"
#include "odometry/core/scan_cadence.hpp"
#include "odometry/core/spin_hold.hpp"
#include "registration/core/parallel.hpp"
#include "registration/core/preprocess.hpp"
#include "registration/core/registration.hpp"

namespace ltm::odometry {

enum class FrameStatus {
    kInitialised,  // first usable scan: the first local map starts at the initial pose
    kTracked,      // registered against the local map
    kRecovered,    // registered again after lost or skipped scans (same segment, consistent)
    // The fit holds but does not fix the position along a direction (observability.hpp): the
    // position there is the motion model's, with its uncertainty in the covariance. Published,
    // not counted as registered.
    kDegenerate,
    // Lost for tracking.restart_after: the local maps are ended and a new one (a new segment)
    // starts with this scan at the best estimate (the prediction). The pose continues the
    // odometry but is a guess relative to the maps before it (large covariance).
    kRestarted,
    kLost,                 // no acceptable registration: prediction carried forward, map unchanged
    kSkippedTooFewPoints,  // empty or tiny scan: prediction carried forward, map unchanged
    kRejectedStamp,        // stamp not finite or not after the previous one: ignored entirely
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
    // The accepted fit's Hessian (sum w J^T J, [dt; dr], local map axes).
    registration::Matrix6d information = registration::Matrix6d::Zero();
    // Observability of the translation (observability.hpp): normalised marginal information,
    // ascending, the directions at or above observability.weak_information, the weakest
    // direction (odometry axes).
    Eigen::Vector3d translation_information = Eigen::Vector3d::Zero();
    int constrained_directions = 0;
    Eigen::Vector3d weak_direction = Eigen::Vector3d::Zero();
    // How the pose was found: "prediction", "search" (the last pose, yaw offsets), "along" (the
    // search along the weak direction moved it), "along (fit confirmed)", "motion model" (the
    // position along the weak direction is the prediction's: kDegenerate).
    const char* search_used = "prediction";
    double profile_support = 0.0;   // the search along the weak direction: best support
    double profile_contrast = 0.0;  // ... over the best rival (0: not searched)
    double profile_shift = 0.0;     // [m] moved along the weak direction by it
    std::size_t input_points = 0;
    std::size_t dropped_non_finite = 0;
    std::size_t dropped_range = 0;
    std::size_t map_points = 0;           // after down-sampling (map grid)
    std::size_t registration_points = 0;  // after down-sampling (registration grid)
    std::size_t correspondences = 0;
    double inlier_fraction = 0.0;  // of the correspondences (registration.inlier_distance)
    double overlap = 0.0;          // correspondences over registration points
    std::size_t inliers = 0;       // correspondences within registration.inlier_distance
    int iterations = 0;            // Gauss-Newton iterations on the fine grid
    int coarse_iterations = 0;     // ... and on the coarse grid (0 without one)
    int attempts = 0;              // registrations run (more than 1: retried, see search)
    // The prediction held the last heading instead of the constant turn rate (a sparse stream
    // whose turns that predicts better: tracking.heading_hold_ratio).
    bool heading_held = false;
    // The spin hold (tracking.spin_rate, spin_hold.hpp): the fit's rotation rate since the last
    // pose or, when larger, the recent rate (tracking.spin_window) [deg/s]; how far the position
    // was moved back along the unobserved directions [m].
    // The recent rate alone when the scan cannot measure its turn (turn_measured false).
    double turn_rate = 0.0;
    double spin_held = 0.0;
    // The fit measured its turn: at most tracking.search_after after the last scan, with the
    // rotation about the turn's axis observed by the registration (the other steps count as no
    // turn in the recent rate).
    bool turn_measured = false;
    bool spin_hold = false;  // held (the scan was degenerate while turning at least spin_rate)
    bool searched = false;   // the prediction failed or was doubtful: search from other guesses
    bool converged = false;
    bool deskewed = false;      // per-point times used to de-skew (at least for the map update)
    double residual_rms = 0.0;  // [m]
    std::uint32_t local_map_id = 0;  // current local map after this frame
    std::uint32_t segment = 0;       // odometry segment (increases at every restart)
    double lost_for = 0.0;  // sensor time since the last tracked scan, when lost or restarted [s]
    bool new_local_map = false;        // this frame started a local map
    std::optional<Keyframe> keyframe;  // set when this frame is a keyframe
    // Wall time of the stages [ms] (measured, for benchmarks and diagnostics).
    double preprocess_ms = 0.0, registration_ms = 0.0, update_ms = 0.0;

    bool pose_valid() const {
        return status == FrameStatus::kInitialised || status == FrameStatus::kTracked ||
               status == FrameStatus::kRecovered || status == FrameStatus::kRestarted ||
               status == FrameStatus::kDegenerate;
    }
    // Registered against the map (a measured pose, not a guess).
    bool registered() const {
        return status == FrameStatus::kTracked || status == FrameStatus::kRecovered;
    }
    bool degenerate() const {
        return status == FrameStatus::kDegenerate || !degenerate_directions.empty();
    }
};

class Odometry {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    explicit Odometry(const OdometryConfig& config, const Eigen::Isometry3d& T_odom_lidar_initial =
                                                        Eigen::Isometry3d::Identity());

    // One scan (LiDAR frame; per-point times, if any, in seconds after cloud.stamp). Never throws
    // on bad data: the status says what happened.
    FrameResult register_frame(const common::PointCloud& cloud);
    // One scan at a known pose (a trajectory from elsewhere: survey, GNSS-INS, another SLAM):
    // everything register_frame does but the registration. The scan is pre-processed, de-skewed
    // (with per-point times) by the motion from the last given pose to this one, added to the
    // local maps at `T_odom_lidar`, and may become a keyframe; local maps start, finish and are
    // handed over as usual. Status kInitialised (first usable scan) or kTracked, pose as given,
    // covariance zero; a non-finite pose is refused (kLost, nothing changes), a bad stamp or a
    // tiny scan as in register_frame. Do not mix with register_frame in one run.
    FrameResult place_frame(const common::PointCloud& cloud, const Eigen::Isometry3d& T_odom_lidar);

    // An optional motion prior from the robot (IMU, wheel odometry), fed by the caller before
    // each scan with its samples up to the end of the sweep; null: none. Not owned.
    void set_prior(MotionPrior* prior) { prior_ = prior; }

    const OdometryConfig& config() const { return config_; }
    // The last pose (estimated or carried forward) and whether any frame was accepted yet.
    const Eigen::Isometry3d& pose() const {
        return motion_.poses() ? motion_.last_pose() : initial_pose_;
    }
    bool initialised() const { return !maps_.empty(); }
    bool lost() const { return lost_; }
    std::uint32_t segment() const { return maps_.segment(); }

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
    // Ends the local maps and starts a new segment with this scan at `predicted` (kRestarted).
    void restart_segment(const std::string& why, const Eigen::Isometry3d& predicted,
                         double since_tracked, FrameResult* r);
    // Refuses a stamp that is not finite or not after the previous one (filling `r`).
    bool stamp_refused(const common::PointCloud& cloud, FrameResult* r);
    // The accepted pose r->T_odom_lidar: the scan into the local maps, keyframe selection.
    void integrate(double stamp, FrameResult* r);
    // Registers the current scan from an initial guess (odometry frame) against the current
    // local map (coarse stage first); fills `r` with the fit and, when it is acceptable, the pose,
    // covariance and degeneracy; returns "" or why it was refused.
    std::string try_register(const Eigen::Isometry3d& guess, double dt, FrameResult* r);
    // The prediction failed or was doubtful: registrations from the last pose and from yaw
    // offsets around the prediction; the best acceptable fit, or why none was.
    std::string search(const Eigen::Isometry3d& predicted, double dt, FrameResult* best);
    // On the coarse grid, every other registration point, with `registration` (the coarse
    // one, or the quick probe of a search guess).
    registration::RegistrationResult coarse_align(const Eigen::Isometry3d& guess_map,
                                                  registration::Registration& registration);
    // After an accepted fit (odometry_observe.cpp): the translation's observability; along a
    // weak direction where the fit's step disagrees with the prediction's (or is long), a search
    // along it and a fit again from the best position. False when the search cannot fix the
    // position there: it is then the prediction's (the caller reports kDegenerate).
    bool check_observability(const Eigen::Isometry3d& predicted, double dt, FrameResult* r);
    // Whether fits of the current scan started `offset` either side of the fit `r` along `v`
    // (odometry axes, unit) both come back to it (observability.basin_tolerance): the fit's
    // position along v is then observed even where the information there is weak.
    bool fit_has_basin(const FrameResult& r, const Eigen::Vector3d& v, double offset, double dt);
    // The published covariance of an accepted fit widened along its weak directions
    // (observability.hpp: the expected step from the prediction and the speed last measured).
    void inflate_covariance(const Eigen::Isometry3d& predicted, double dt, FrameResult* r) const;
    // A degenerate scan turning at least tracking.spin_rate: its position along the directions
    // it did not observe held at the last pose (spin_hold.hpp). `kept_out`: degenerate by the
    // observability check (then every weak direction is unobserved).
    void hold_while_spinning(bool kept_out, FrameResult* r) const;
    // Whether a turn rate [deg/s] is a spin (tracking.spin_rate; never with wheel odometry).
    bool spinning(double rate) const;
    bool excellent(const FrameResult& r) const;
    bool doubtful(const FrameResult& r) const;
    void learn(const FrameResult& r);
    void accept(const FrameResult& result);

    OdometryConfig config_;
    Eigen::Isometry3d initial_pose_;
    registration::ParallelFor parallel_;
    registration::Preprocessor preprocessor_;
    registration::Registration registration_;
    registration::Registration coarse_registration_;  // used when the maps have a coarse grid
    registration::Registration probe_registration_;   // a search guess's quick coarse alignment
    MotionModel motion_;
    MotionPrior* prior_ = nullptr;
    LocalMapSet maps_;
    KeyframeSelector keyframes_;
    std::uint64_t next_keyframe_id_ = 0;
    double typical_rms_ = 0.0;      // running mean of the tracked frames' residual RMS [m]
    double typical_inliers_ = 0.0;  // ... and of their inlier fraction
    double typical_overlap_ = 0.0;  // ... and of their overlap
    // The same over the first tracked frames of the run (against a young map), the yardstick
    // after a restart: the new map is as young.
    double early_rms_ = 0.0, early_inliers_ = 0.0, early_overlap_ = 0.0;
    int early_frames_ = 0;
    bool lost_ = false;
    bool unobserved_ = false;      // the last fit was degenerate: the velocity is a guess
    double observed_speed_ = 0.0;  // [m/s] of the last registered scan constrained every way
    RecentTurnRate recent_turn_;   // the published steps' rotation rate (tracking.spin_window)
    static constexpr int kYoungSegmentScans = 10;  // scans that enter a new segment's map anyway
    int segment_scans_ = 0;                        // scans integrated since the segment began
    int kept_out_run_ = 0;  // degenerate scans kept out of the map in a row (after the young ones)
    double last_tracked_stamp_ = 0.0;  // of the last scan with a valid pose
    Eigen::Isometry3d last_tracked_pose_ = Eigen::Isometry3d::Identity();
    bool has_stamp_ = false;
    double last_stamp_ = 0.0;
    HeadingSkill heading_;  // constant turn rate or held heading, for sparse streams
    ScanCadence cadence_;   // the stream's usual interval between scans (tracking.restart_gap)
    registration::PreprocessedScan scan_;         // reused buffers
    std::vector<Eigen::Vector3f> coarse_points_;  // every other registration point of scan_
};

}  // namespace ltm::odometry
