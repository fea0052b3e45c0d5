#pragma once
// Localisation on a saved map, scan by scan (METHOD.md section 6): global localisation until the
// first fix, then tracking (scan-to-map registration against the map's voxels, seeded by the
// odometry's motion since the last scan), its quality checked every scan; when tracking fails for
// a while, or the scan fits the map only somewhere else (a kidnap), or the odometry restarted,
// global localisation runs again by itself. Beyond the map's edge the pose follows the odometry
// (map_to_odom held) and the state says so.
//
// Output: the LiDAR's pose in the map and map_to_odom (T_map_odom = T_map_lidar T_odom_lidar^-1),
// the transform a robot's TF tree needs between the map and its odometry frame.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/core/config_check.hpp"
#include "common/core/sensor_preset.hpp"
#include "localisation/core/global_localiser.hpp"
#include "localisation/core/global_query.hpp"
#include "localisation/core/localisation_map.hpp"
#include "localisation/core/neighbourhood_builder.hpp"
#include "registration/core/registration.hpp"
#include "registration/core/registration_config.hpp"
#include "registration/core/sector_overlap.hpp"

namespace ltm::localisation {

enum class LocalisationState : std::uint8_t {
    kInitialising = 0,  // no fix yet (the start pose is unknown)
    kTracking = 1,      // registered to the map this scan
    kLost = 2,          // tracking failed: global localisation runs until it answers
    kRelocalised = 3,   // this scan: a fix by global localisation (start, or after lost)
    kOffMap = 4,        // beyond the map: the pose follows the odometry, map_to_odom held
};
const char* to_string(LocalisationState state);

struct LocaliserConfig {
    GlobalLocaliserConfig global;
    // Tracking: scan-to-map registration (the odometry's fine settings) on at most max_points
    // points down-sampled on a grid of `downsample` [m].
    registration::RegistrationConfig tracking;
    double downsample = 1.0;
    int max_points = 3000;
    double min_inlier_fraction = 0.5;  // of the correspondences
    double min_overlap = 0.3;          // correspondences / points
    // Of the points on structure (surfaces that are not ground-like) with a map surface within
    // reach, this share must be inliers (|IMLS distance| < inlier_distance): the ground fits
    // anywhere, so a scan registered at the wrong place still has most points on a surface.
    double min_structure_inlier_ratio = 0.7;
    int min_structure_points = 50;  // fewer on structure (open ground): not checked
    double inlier_distance = 0.3;   // [m]
    // A registration that moves the pose more than this from the odometry's prediction is not
    // tracking: the robot was moved or the odometry failed [m], [deg].
    double max_correction_translation = 1.0;
    double max_correction_rotation = 5.0;
    double lost_after = 0.5;      // tracking failed this long (sensor time): lost [s]
    double global_every = 0.0;    // while lost: global localisation at most this often [s]
    double off_map_margin = 8.0;  // no map voxel within this of the pose: off the map [m]
    // A registration that finds map surfaces for fewer than this share of the scan's points
    // (but at least min_overlap) sees only the map's edge: voxels seen from afar, few and far
    // apart, pull the pose by centimetres a scan along the road; it is not used, the pose
    // follows the odometry from the last scan the map covered better (off the map) [0..1].
    // 0: every registration that passes is used.
    double edge_overlap = 0.0;
    // The same direction by direction (registration/core/sector_overlap.hpp): a registration whose
    // weakest azimuth sector (of edge_sectors, holding at least 10 % of the points) has fewer
    // than this share of its points explained (inliers) is at the map's edge too. Leaving the
    // map, the side ahead empties while the scan as a whole is still explained (site_week day 2:
    // tracked 40 m past day 0's ground with overall overlap >= 0.5, the pose pulled back along
    // the road by 0.02-0.03 m more). 0: off.
    double edge_sector_overlap = 0.0;
    int edge_sectors = 4;
    // Gap between scans (sensor time) after which the odometry's motion is not trusted and
    // global localisation checks the pose [s].
    double max_gap = 1.0;
    // Tracking on the paged map's neighbourhood of the pose (neighbourhood_builder.hpp), used
    // by load_localiser (component/loaded_localiser.hpp); radius 0: the whole map.
    NeighbourhoodConfig neighbourhood;
};

template <class Visitor>
void visit_fields(LocaliserConfig& c, Visitor&& v) {
    using namespace common::rules;
    visit_fields(c.global, "global.", v);
    registration::visit_fields(c.tracking, "tracking.", v);
    v("downsample", c.downsample, non_negative);
    v("max_points", c.max_points, at_least(100));
    v("min_inlier_fraction", c.min_inlier_fraction, unit);
    v("min_overlap", c.min_overlap, unit);
    v("min_structure_inlier_ratio", c.min_structure_inlier_ratio, unit);
    v("min_structure_points", c.min_structure_points, non_negative);
    v("inlier_distance", c.inlier_distance, positive);
    v("max_correction_translation", c.max_correction_translation, positive);
    v("max_correction_rotation", c.max_correction_rotation, positive);
    v("lost_after", c.lost_after, non_negative);
    v("global_every", c.global_every, non_negative);
    v("off_map_margin", c.off_map_margin, positive);
    v("edge_overlap", c.edge_overlap, unit);
    v("edge_sector_overlap", c.edge_sector_overlap, unit);
    v("edge_sectors", c.edge_sectors, in_range(1, 36));
    v("max_gap", c.max_gap, positive);
    v("neighbourhood.radius", c.neighbourhood.radius, non_negative);
    v("neighbourhood.rebuild_distance", c.neighbourhood.rebuild_distance, positive);
    v("neighbourhood.page_above_mb", c.neighbourhood.page_above_mb, non_negative);
}

std::optional<common::ConfigProblem> validate(const LocaliserConfig& config);

// The settings for a sensor preset (its row of common/core/sensor_preset.hpp): global verification
// as the mapper's loop verification for that sensor (a narrow field of view has fewer points), the
// off-map margin; the rest the defaults.
LocaliserConfig localiser_preset(common::SensorPreset preset);
// The map's settings for a sensor preset (the query's local features are made with them).
LocalisationMapConfig localisation_map_preset(common::SensorPreset preset);

// The odometry's estimate for the scan: its pose in the odometry frame and its segment (a new
// segment: the odometry restarted and its frame is no longer the same).
struct OdometryInput {
    Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();
    std::uint32_t segment = 0;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct LocalisationUpdate {
    double stamp = 0.0;
    LocalisationState state = LocalisationState::kInitialising;
    bool pose_valid = false;  // false while initialising or lost
    Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_map_odom = Eigen::Isometry3d::Identity();
    registration::Matrix6d covariance = registration::Matrix6d::Identity();  // [dt; dr]
    double confidence = 0.0;                                                 // 0..1
    double inlier_fraction = 0.0;   // of this scan's registration
    double overlap = 0.0;           // of this scan's registration: correspondences / points
    bool global_ran = false;        // global localisation ran on this scan (elsewhere: its
                                    // answer came with this scan)
    double global_time_s = 0.0;     // its wall time
    bool global_asked = false;      // elsewhere: a global query was asked for this scan
    double global_carried_s = 0.0;  // elsewhere: the answer's scan was this long before this one
    double lost_for = 0.0;          // sensor time since the last good registration [s]
    double since_fix = 0.0;         // sensor time since the last global fix [s]
    std::string message;            // one line: what happened (why lost, how relocalised)
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

class Localiser {
  public:
    // Throws common::ConfigError (naming the key) on an invalid configuration.
    Localiser(std::shared_ptr<const LocalisationMap> map, const LocaliserConfig& config = {});

    // An initial pose hint (RViz "2D Pose Estimate"): the next global localisation searches
    // around it; radius 0: the config's hint_radius. Forces a global localisation.
    void set_initial_pose(const PoseHint& hint);

    // points: the scan in its LiDAR frame, pre-processed as the map's keyframes were. odometry:
    // the odometry's pose of the scan (nullopt: none; tracking then starts from the last pose).
    LocalisationUpdate process(double stamp, const std::vector<Eigen::Vector3f>& points,
                               const std::optional<OdometryInput>& odometry = std::nullopt);

    // Global localisation elsewhere (GlobalHandOver, global_query.hpp): process() never runs a
    // global query itself; it asks one (take_request(), for another thread to answer with
    // answer()) and applies the answer handed back (give_answer()) to the next scan it processes,
    // carried forward by the odometry. Meanwhile it keeps tracking when it has a fix, and says
    // "searching" (no valid pose) when it has none. Off (the default): the query runs inside
    // process() on the scan that needs it (offline, deterministic).
    void set_global_elsewhere(bool on) { elsewhere_ = on; }
    bool global_elsewhere() const { return elsewhere_; }
    // The query asked by the last process() (at most one out at a time), once.
    std::optional<GlobalRequest> take_request();
    // The answer to the query out: applied by the next process().
    void give_answer(GlobalAnswer answer) { answer_ = std::move(answer); }
    bool global_busy() const { return handover_.busy(); }

    // Goes on from another localiser's track (the same site's next version, whose map frame
    // stays put): its state, pose, map_to_odom and odometry continue here, so the next scan is
    // tracked on this map without a global localisation (one runs as usual when the other was
    // initialising or lost). An initial pose hint given to the other is not taken. Where the
    // global localisation runs elsewhere, a query out for the other answers for this one.
    void take_track(const Localiser& from);
    LocalisationState state() const { return state_; }
    const LocalisationMap& map() const { return *map_; }

    // A paged map (issue 28 item 3): tracking registers to the builder's neighbourhood of the pose
    // instead of the whole map's voxels, and after each scan with a valid pose tells the builder
    // where it is (a finished neighbourhood is swapped in, a new one asked for off this thread).
    // Null (the default): the whole map's voxels.
    void set_neighbourhood(std::shared_ptr<NeighbourhoodBuilder> builder) {
        neighbourhood_ = std::move(builder);
    }
    const std::shared_ptr<NeighbourhoodBuilder>& neighbourhood() const { return neighbourhood_; }
    const LocaliserConfig& config() const { return config_; }

  private:
    bool run_global(double stamp, const std::vector<Eigen::Vector3f>& points,
                    const Eigen::Isometry3d& T_odom_lidar, LocalisationUpdate* u);
    // Elsewhere (localiser_global.cpp): the answer waiting applied to this scan (true:
    // relocalised), and a query asked for it.
    bool apply_answer(double stamp, const Eigen::Isometry3d& T_odom_lidar, LocalisationUpdate* u);
    void ask_global(double stamp, const std::vector<Eigen::Vector3f>& points,
                    const Eigen::Isometry3d& T_odom_lidar, LocalisationUpdate* u);
    void finish(double stamp, LocalisationUpdate* u);
    bool track(const Eigen::Isometry3d& predicted, LocalisationUpdate* u);
    // The weakest direction of the sampled scan at T_map_lidar (edge_sector_overlap; off: none).
    registration::SectorOverlap weakest_sector(const Eigen::Isometry3d& T_map_lidar) const;
    void thin(const std::vector<Eigen::Vector3f>& points);
    // What tracking registers to: the neighbourhood's fine grid, or the whole map's.
    const registration::VoxelGrid& tracking_grid() const;

    std::shared_ptr<const LocalisationMap> map_;
    std::shared_ptr<NeighbourhoodBuilder> neighbourhood_;
    LocaliserConfig config_;
    GlobalLocaliser global_;
    registration::Registration tracker_;
    registration::VoxelDownsampler sampler_;
    std::vector<Eigen::Vector3f> sampled_;

    LocalisationState state_ = LocalisationState::kInitialising;
    std::optional<PoseHint> hint_;
    bool have_fix_ = false;
    Eigen::Isometry3d T_map_odom_ = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d T_map_lidar_ = Eigen::Isometry3d::Identity();   // last estimate
    Eigen::Isometry3d T_odom_lidar_ = Eigen::Isometry3d::Identity();  // last odometry
    std::uint32_t segment_ = 0;
    bool have_odometry_ = false;
    double last_stamp_ = 0.0, last_good_ = 0.0, last_fix_ = 0.0, last_global_ = -1e300;
    bool first_ = true;

    bool elsewhere_ = false;
    bool recheck_ = false;  // an answer was dropped (stale): ask again
    GlobalHandOver handover_;
    std::optional<GlobalRequest> request_;
    std::optional<GlobalAnswer> answer_;
};

}  // namespace ltm::localisation
