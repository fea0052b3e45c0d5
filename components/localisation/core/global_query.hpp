#pragma once
// Global localisation off the tracking thread (issue 28): the hand-over between the localiser,
// which tracks every scan, and a global query (ScanContext++ retrieval, RANSAC, verification:
// 0.03-0.3 s) that runs elsewhere while tracking goes on.
//
// The localiser asks a query for one scan (GlobalRequest: the scan's points, its odometry pose and
// segment, the initial-pose hint). At most one query is out at a time: a scan that would ask while
// one is out asks nothing, so the next query is always made from the newest scan after the answer
// (never a stale queued one). The answer (GlobalAnswer) is the pose of the scan it was asked for;
// it is applied to a later scan by carrying it forward with the odometry since then:
//   T_map_odom = T_map_lidar(asked) T_odom_lidar(asked)^-1,  T_map_lidar(now) = T_map_odom
//   T_odom_lidar(now)
// so a pose from the past is never reported as now. An answer is stale (dropped, said why) when
// the odometry restarted since it was asked (another odometry frame) or an initial pose came since
// (the operator's newer word).
//
// No threads here: GlobalHandOver is the localiser's bookkeeping (one thread), answer() runs a
// query with a GlobalLocaliser of its own (not shared with tracking: it keeps scratch state).
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "localisation/core/global_localiser.hpp"

namespace ltm::localisation {

struct GlobalRequest {
    std::uint64_t id = 0;
    double stamp = 0.0;                   // the scan's
    std::vector<Eigen::Vector3f> points;  // the scan, pre-processed as the map's keyframes were
    Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();  // the scan's odometry pose
    std::uint32_t segment = 0;                                       // its odometry segment
    std::optional<PoseHint> hint;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct GlobalAnswer {
    std::uint64_t id = 0;  // the request's
    double stamp = 0.0;    // the scan asked for
    Eigen::Isometry3d T_odom_lidar = Eigen::Isometry3d::Identity();
    std::uint32_t segment = 0;
    GlobalLocalisation result;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

// Runs the query (on the caller's thread: the component's `localisation/global`).
GlobalAnswer answer(GlobalLocaliser& global, const GlobalRequest& request);

// map -> odometry frame from an answer (valid while the odometry's segment is the answer's).
Eigen::Isometry3d answer_T_map_odom(const GlobalAnswer& a);
// The answer's pose carried forward to a later scan of the same odometry segment.
Eigen::Isometry3d carry_forward(const GlobalAnswer& a, const Eigen::Isometry3d& T_odom_lidar_now);

class GlobalHandOver {
  public:
    bool busy() const { return out_.has_value(); }
    // Sensor time of the scan the query out was asked for (busy() only).
    double asked_stamp() const { return out_ ? out_->stamp : 0.0; }

    // A request for this scan, or nothing while one is out (one query at a time).
    std::optional<GlobalRequest> ask(double stamp, const std::vector<Eigen::Vector3f>& points,
                                     const Eigen::Isometry3d& T_odom_lidar, std::uint32_t segment,
                                     const std::optional<PoseHint>& hint);

    // An initial pose came: the answer to the query out (asked without it) will be stale.
    void hint_changed() { hint_generation_++; }

    enum class Fate { kApply, kStale, kUnknown };
    // The answer to the query out: kApply when it is still good for the odometry's current
    // segment, kStale (why says why) when the odometry restarted or a hint came since it was
    // asked, kUnknown when no query with its id is out (a duplicate). Either way the query is no
    // longer out (except kUnknown).
    Fate receive(const GlobalAnswer& a, std::uint32_t segment_now, std::string* why);

  private:
    struct Out {
        std::uint64_t id;
        double stamp;
        std::uint64_t hint_generation;
    };
    std::optional<Out> out_;
    std::uint64_t next_id_ = 1, hint_generation_ = 0;
};

}  // namespace ltm::localisation
