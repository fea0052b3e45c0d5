#include "localisation/core/new_site_pose.hpp"

#include <utility>

namespace ltm::localisation {

const char* const kNewSitePoseNames = "slam_map_to_odom, slam_odometry or odometry";

std::optional<NewSitePoseSource> parse_new_site_pose(const std::string& name) {
    if (name == "slam_map_to_odom") return NewSitePoseSource::kSlamMapToOdom;
    if (name == "slam_odometry") return NewSitePoseSource::kSlamOdometry;
    if (name == "odometry") return NewSitePoseSource::kBaseStation;
    return std::nullopt;
}

bool NewSitePose::frame_is_ours() const {
    return source_ != NewSitePoseSource::kBaseStation || (base_version_ && base_version_->empty());
}

std::vector<LocalisationUpdate> NewSitePose::map_to_odom(const Eigen::Isometry3d& T_map_odom) {
    T_map_odom_ = T_map_odom;
    std::vector<LocalisationUpdate> out;
    out.reserve(waiting_.size());
    for (const OdometryPose& o : waiting_) out.push_back(posed(o, T_map_odom));
    waiting_.clear();
    return out;
}

LocalisationUpdate NewSitePose::posed(const OdometryPose& o,
                                      const Eigen::Isometry3d& T_map_odom) const {
    LocalisationUpdate u;
    u.stamp = o.stamp;
    u.state = LocalisationState::kOffMap;
    u.pose_valid = true;
    u.T_map_lidar = T_map_odom * o.T_odom_lidar;
    u.T_map_odom = T_map_odom;
    u.covariance = o.covariance;
    u.message = source_ == NewSitePoseSource::kBaseStation
                    ? "no map yet: the odometry under the base station's map_to_odom, not localised"
                    : "new site: the pose of the map being made (the odometry under the SLAM's "
                      "map_to_odom)";
    return u;
}

std::optional<LocalisationUpdate> NewSitePose::odometry(const OdometryPose& o) {
    if (source_ == NewSitePoseSource::kSlamMapToOdom) {
        if (T_map_odom_) return posed(o, *T_map_odom_);
        if (waiting_.size() == kMaxWaiting) {
            waiting_.pop_front();
            ++dropped_;
        }
        waiting_.push_back(o);
        return std::nullopt;
    }
    if (source_ == NewSitePoseSource::kSlamOdometry) return std::nullopt;  // slam_pose's
    LocalisationUpdate u;
    u.stamp = o.stamp;
    u.state = LocalisationState::kOffMap;
    if (offered_) {
        u.message =
            "no map yet: the base station's version is on its way (no pose until it is here)";
    } else if (!base_version_) {
        u.message =
            "no map yet: odometry only (the base station has not said which site version its "
            "map_to_odom belongs to)";
    } else if (!frame_is_ours()) {
        u.message = "no map yet: the base station's map_to_odom belongs to site version " +
                    *base_version_ +
                    ", which this robot does not have yet (no pose until it is here)";
    } else if (!T_map_odom_) {
        u.message = "no map yet: odometry only (no map_to_odom from the base station yet)";
    } else {
        return posed(o, *T_map_odom_);
    }
    return u;
}

LocalisationUpdate NewSitePose::slam_pose(double stamp, const Eigen::Isometry3d& T_map_lidar,
                                          const registration::Matrix6d& covariance) {
    LocalisationUpdate u;
    u.stamp = stamp;
    u.state = LocalisationState::kOffMap;
    u.pose_valid = true;
    u.T_map_lidar = T_map_lidar;
    u.covariance = covariance;
    u.message = "new site: the pose of the map being made (SLAM)";
    return u;
}

std::string NewSitePose::start_line() const {
    switch (source_) {
        case NewSitePoseSource::kBaseStation:
            return "new site: no map yet (the odometry under the base station's map_to_odom is "
                   "the pose meanwhile, never localised)";
        case NewSitePoseSource::kSlamOdometry:
            return "new site: no map yet, nothing to localise on until the next session (the "
                   "SLAM's pose, slam_odometry, is the map pose meanwhile)";
        case NewSitePoseSource::kSlamMapToOdom:
            break;
    }
    return "new site: no map yet, nothing to localise on until the next session (the odometry "
           "under the SLAM's map_to_odom, slam_map_to_odom, is the map pose meanwhile)";
}

}  // namespace ltm::localisation
