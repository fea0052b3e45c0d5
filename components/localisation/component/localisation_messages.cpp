#include "localisation/component/localisation_messages.hpp"

#include <algorithm>
#include <cmath>

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::localisation {

std::uint8_t to_msg_state(LocalisationState state) {
    switch (state) {
        case LocalisationState::kInitialising:
            return ltm_msgs_msg_LocalisationStatus_Constants_INITIALISING;
        case LocalisationState::kTracking:
            return ltm_msgs_msg_LocalisationStatus_Constants_TRACKING;
        case LocalisationState::kLost:
            return ltm_msgs_msg_LocalisationStatus_Constants_LOST;
        case LocalisationState::kRelocalised:
            return ltm_msgs_msg_LocalisationStatus_Constants_RELOCALISED;
        case LocalisationState::kOffMap:
            return ltm_msgs_msg_LocalisationStatus_Constants_OFF_MAP;
    }
    return ltm_msgs_msg_LocalisationStatus_Constants_INITIALISING;
}

convert::Owned<msg::LocalisationStatus> status_msg(const LocalisationUpdate& u,
                                                   const StatusCounters& counters,
                                                   const std::string& frame_id) {
    convert::Owned<msg::LocalisationStatus> m = status_msg(u.stamp, u.message, counters, frame_id);
    m->state = to_msg_state(u.state);
    m->pose_valid = u.pose_valid;
    m->confidence = static_cast<float>(u.confidence);
    m->inlier_fraction = static_cast<float>(u.inlier_fraction);
    m->lost_for = u.lost_for;
    m->since_fix = u.since_fix;
    m->global_ran = u.global_ran;
    m->global_time = u.global_time_s;
    return m;
}

convert::Owned<msg::LocalisationStatus> status_msg(double stamp, const std::string& message,
                                                   const StatusCounters& counters,
                                                   const std::string& frame_id) {
    convert::Owned<msg::LocalisationStatus> m;
    m->header.stamp = convert::to_time(stamp);
    convert::set_string(m->header.frame_id, frame_id);
    m->state = ltm_msgs_msg_LocalisationStatus_Constants_INITIALISING;
    m->relocalisations = counters.relocalisations;
    m->skipped_scans = counters.skipped_scans;
    convert::set_string(m->message, message);
    return m;
}

convert::Owned<msg::PoseWithCovarianceStamped> pose_msg(const LocalisationUpdate& u,
                                                        const std::string& frame_id) {
    convert::Owned<msg::PoseWithCovarianceStamped> m;
    m->header.stamp = convert::to_time(u.stamp);
    convert::set_string(m->header.frame_id, frame_id);
    m->pose.pose = convert::to_pose(u.T_map_lidar);
    convert::to_array36(u.covariance, m->pose.covariance);
    return m;
}

PoseHint hint_from_msg(const msg::PoseWithCovarianceStamped& m, const HintRadius& radius) {
    PoseHint hint;
    hint.T_map_lidar = convert::to_isometry(m.pose.pose);
    const double variance = std::max(m.pose.covariance[0], m.pose.covariance[7]);  // x x, y y
    const double sigma = std::isfinite(variance) && variance > 0.0 ? std::sqrt(variance) : 0.0;
    hint.radius = std::max(radius.min_radius, radius.sigmas * sigma);
    return hint;
}

}  // namespace ltm::localisation
