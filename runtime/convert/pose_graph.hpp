#pragma once
// ltm_msgs/PoseGraph: the global map as anchors (local maps at their optimised poses) and the
// edges between them, named by local map ids.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/convert/owned_message.hpp"
#include "runtime/messages.hpp"

namespace ltm::convert {

enum class GraphEdgeKind : std::uint8_t {
    kOdometry = ltm_msgs_msg_PoseGraphEdge_Constants_ODOMETRY,
    kLoop = ltm_msgs_msg_PoseGraphEdge_Constants_LOOP,
    kSession = ltm_msgs_msg_PoseGraphEdge_Constants_SESSION,
};

struct GraphAnchor {
    std::uint64_t local_map_id = 0;
    Eigen::Isometry3d T_map_anchor = Eigen::Isometry3d::Identity();
};

struct GraphEdge {
    std::uint64_t from_map_id = 0, to_map_id = 0;
    GraphEdgeKind kind = GraphEdgeKind::kOdometry;
    Eigen::Isometry3d T_from_to = Eigen::Isometry3d::Identity();
    Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Identity();
};

struct PoseGraphData {
    msg::Time stamp{};
    std::string frame_id;        // the map frame
    std::uint32_t revision = 0;  // increases with every optimisation
    std::vector<GraphAnchor> anchors;
    std::vector<GraphEdge> edges;
};

Owned<msg::PoseGraph> to_msg(const PoseGraphData& graph);
PoseGraphData from_msg(const msg::PoseGraph& message);

}  // namespace ltm::convert
