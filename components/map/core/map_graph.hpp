#pragma once
// The graph a map carries (what PoseGraph optimises, what the map files store): nodes are the
// anchor poses of the local maps, edges relative anchor poses (odometry edges between consecutive
// maps, loop edges from verified loop closures). Plain data: the optimisation is mapping's.
#include <Eigen/Geometry>
#include <cstdint>

namespace ltm::map {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

enum class EdgeKind : std::uint8_t { kOdometry = 0, kLoop = 1 };
const char* to_string(EdgeKind kind);

struct PoseGraphNode {
    std::uint64_t id = 0;
    std::uint32_t session = 0;
    std::uint64_t local_map_id = 0;  // the odometry's id of the local map (within its session)
    Eigen::Isometry3d T_odom_anchor = Eigen::Isometry3d::Identity();   // odometry's estimate
    Eigen::Isometry3d T_world_anchor = Eigen::Isometry3d::Identity();  // optimised estimate
    bool fixed = false;  // held constant by the optimisation
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

struct PoseGraphEdge {
    std::uint64_t from = 0, to = 0;  // node ids; the measurement is T_from_to
    EdgeKind kind = EdgeKind::kOdometry;
    Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();
    Matrix6d information = Matrix6d::Identity();  // of e = [dt; dr]
    bool active = true;              // loop edges: false after the last optimisation rejected it
    double error_translation = 0.0;  // |t(E)| after the last optimisation [m]
    double error_rotation = 0.0;     // angle of E after the last optimisation [rad]
    // Loop edges: the keyframes that produced it (the caller's keyframe indices).
    std::uint64_t query_keyframe = 0, match_keyframe = 0;
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

}  // namespace ltm::map
