#pragma once
// The long-term map's folding (LongTermConfig, mapper.hpp): where each local map of an open
// session that was folded into an earlier lap's or session's map went, the graph without a folded
// node (its edges moved to the node it went into), and the odometry edges made through a folded
// map (their nodes' odometry paths are of other laps). Owns that record; the Mapper decides when
// to fold and moves the voxels, keyframes and loops.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "mapping/core/pose_graph.hpp"

namespace ltm::mapping {

class LongTermFolding {
  public:
    // A local map of an open session folded into an earlier map (its node).
    struct Folded {
        std::uint64_t node = 0;
        Eigen::Isometry3d T_node_anchor = Eigen::Isometry3d::Identity();  // its anchor there
        Eigen::Isometry3d T_odom_anchor = Eigen::Isometry3d::Identity();
        std::uint32_t segment = 0;
        double path = 0.0;  // odometry path to its anchor [m]
        EIGEN_MAKE_ALIGNED_OPERATOR_NEW
    };

    // Where local map `local_map_id` of `session` went, or nullptr when it was not folded.
    const Folded* find(std::uint32_t session, std::uint64_t local_map_id) const;
    void record(std::uint32_t session, std::uint64_t local_map_id, const Folded& folded);
    // Node `n` was folded into `into` (n's anchor at T_into_n there): the maps folded into n
    // before now name `into`. Their (session, local map id), for the chains to follow.
    std::vector<std::pair<std::uint32_t, std::uint64_t>> retarget(
        std::uint64_t n, std::uint64_t into, const Eigen::Isometry3d& T_into_n);

    // An odometry edge (from, to) made through a folded map.
    void relay(std::uint64_t from, std::uint64_t to) { relayed_.insert({from, to}); }
    bool relayed(std::uint64_t from, std::uint64_t to) const {
        return relayed_.count({from, to}) > 0;
    }

    // `graph` without node `n`: its edges name `into`, measured from its anchor (T_into_n, n's
    // anchor in into's). An edge between the two disappears (the merge holds it); an odometry edge
    // between two places already joined by one, or a loop edge beyond
    // `max_loops_per_anchor_pair` (0: no limit), is left out. The relayed edges follow.
    PoseGraph without(const PoseGraph& graph, std::uint64_t n, std::uint64_t into,
                      const Eigen::Isometry3d& T_into_n, int max_loops_per_anchor_pair);

    std::size_t memory_bytes() const;

  private:
    // Per session: local map id -> where it went.
    std::map<std::uint32_t, std::map<std::uint64_t, Folded>> folded_;
    std::set<std::pair<std::uint64_t, std::uint64_t>> relayed_;  // odometry edges (from, to)
};

}  // namespace ltm::mapping
