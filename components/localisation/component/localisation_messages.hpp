#pragma once
// The localiser's results and inputs as messages: ltm_msgs/LocalisationStatus, the pose in the map
// (geometry_msgs/PoseWithCovarianceStamped) and an initial pose hint from one (RViz's "2D Pose
// Estimate" on `initialpose`).
#include <cstdint>
#include <string>

#include "localisation/core/localiser.hpp"
#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::localisation {

// What the component adds to an update: counters since the start.
struct StatusCounters {
    std::uint32_t relocalisations = 0;
    std::uint32_t skipped_scans = 0;
};

std::uint8_t to_msg_state(LocalisationState state);

convert::Owned<msg::LocalisationStatus> status_msg(const LocalisationUpdate& u,
                                                   const StatusCounters& counters,
                                                   const std::string& frame_id);

// A status that belongs to no processed scan (no map: why): state initialising, pose not valid.
convert::Owned<msg::LocalisationStatus> status_msg(double stamp, const std::string& message,
                                                   const StatusCounters& counters,
                                                   const std::string& frame_id);

// T_map_lidar with the update's covariance ([dt; dr], ROS's x y z rx ry rz order).
convert::Owned<msg::PoseWithCovarianceStamped> pose_msg(const LocalisationUpdate& u,
                                                        const std::string& frame_id);

// The search radius of an initial pose: `sigmas` standard deviations of its horizontal position
// (the larger of the x and y variances), at least `min_radius` [m].
struct HintRadius {
    double sigmas = 3.0;
    double min_radius = 2.0;  // [m]
};
PoseHint hint_from_msg(const msg::PoseWithCovarianceStamped& m, const HintRadius& radius = {});

}  // namespace ltm::localisation
