#pragma once
// How far the graph's estimate of the relative pose of two anchors can have drifted: the shortest
// odometry distance between them through the graph, where a loop edge (a direct measurement)
// counts as no distance. Along one session without loops it is the odometry path between them;
// once loops join laps of a route, it is the odometry between their nearest joined places.
#include <cstdint>
#include <functional>

#include "mapping/core/pose_graph.hpp"

namespace ltm::mapping {

// odometry_length(edge) is an odometry edge's length [m] (>= 0), or +infinity for an edge that
// bounds nothing (the edge into a new odometry segment: the odometry lost track there). Loop
// edges that the last optimisation disabled are not used. +infinity when the nodes are not
// connected but through such edges.
double drift_distance(const PoseGraph& graph, std::uint64_t from, std::uint64_t to,
                      const std::function<double(const map::PoseGraphEdge&)>& odometry_length);

}  // namespace ltm::mapping
