#pragma once
// A site with no version yet (nothing to localise on): where the map pose of the map being made
// today comes from (the localisation component's `new_site_pose`). Every such pose is OFF_MAP,
// never "localised".
//  - kSlamMapToOdom (`slam_map_to_odom`, the default; the composed lifelong mode): each odometry
//    pose under the mapping's newest map_to_odom. The pose goes out as soon as the odometry's does:
//    the mapping's own thread (its saves, the maintenance's edits of its local maps: 0.1-0.4 s
//    each) never delays it. Poses that come before the first map_to_odom wait for it (at most
//    kMaxWaiting, the oldest dropped), as the mapping's corrected odometry waits for its first
//    local map.
//  - kSlamOdometry (`slam_odometry`): the mapping's corrected odometry (frame map) is the pose; it
//    waits for whatever the mapping's thread is doing.
//  - kBaseStation (`odometry`, the split robot: no SLAM on it): each odometry pose under the base
//    station's map_to_odom, only while the base station's mapping says that frame belongs to no
//    version (a new site there too) and no version is on its way (an offer: its frame is not this
//    session's yet); otherwise a status line only, no pose.
#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "localisation/core/localiser.hpp"

namespace ltm::localisation {

enum class NewSitePoseSource { kSlamMapToOdom, kSlamOdometry, kBaseStation };

// "slam_map_to_odom", "slam_odometry" or "odometry"; nullopt for another name.
std::optional<NewSitePoseSource> parse_new_site_pose(const std::string& name);
extern const char* const kNewSitePoseNames;  // for the one-line error

// An odometry pose (frame odom), as the odometry published it.
struct OdometryPose {
    double stamp = 0.0;
    Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();
    registration::Matrix6d covariance = registration::Matrix6d::Identity();
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

class NewSitePose {
  public:
    static constexpr std::size_t kMaxWaiting = 300;  // poses waiting for the first map_to_odom

    explicit NewSitePose(NewSitePoseSource source) : source_(source) {}
    NewSitePoseSource source() const { return source_; }
    // The pose is the odometry's under a map_to_odom (not the mapping's corrected odometry).
    bool composes_odometry() const { return source_ != NewSitePoseSource::kSlamOdometry; }

    // The mapping's map_to_odom (kBaseStation: the base station's). kSlamMapToOdom: the updates of
    // the poses that waited for the first one, oldest first.
    std::vector<LocalisationUpdate> map_to_odom(const Eigen::Isometry3d& T_map_odom);
    void offered() { offered_ = true; }                                 // kBaseStation
    void base_version(std::string v) { base_version_ = std::move(v); }  // kBaseStation
    // The map_to_odom's frame is this session's map frame (kBaseStation: a new site on both sides).
    bool frame_is_ours() const;

    // One odometry pose: its update (a pose, or kBaseStation a status line without one); nullopt
    // while it waits for the first map_to_odom (kSlamMapToOdom), and always for kSlamOdometry.
    std::optional<LocalisationUpdate> odometry(const OdometryPose& o);
    // kSlamOdometry: the mapping's corrected pose (frame map).
    static LocalisationUpdate slam_pose(double stamp, const Eigen::Isometry3d& T_map_lidar,
                                        const registration::Matrix6d& covariance);

    std::size_t dropped() const { return dropped_; }  // waited too long (kSlamMapToOdom)
    // What the component says at the start: where the pose comes from meanwhile.
    std::string start_line() const;

  private:
    LocalisationUpdate posed(const OdometryPose& o, const Eigen::Isometry3d& T_map_odom) const;

    NewSitePoseSource source_;
    std::optional<Eigen::Isometry3d> T_map_odom_;
    bool offered_ = false;
    std::optional<std::string> base_version_;
    std::deque<OdometryPose> waiting_;
    std::size_t dropped_ = 0;
};

}  // namespace ltm::localisation
