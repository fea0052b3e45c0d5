#pragma once
// Each session's odometry chain (mapper.hpp): its local maps in id order as graph nodes, the
// odometry edge between neighbours (the weak edge across a segment break), the odometry path to
// each node, and where a new node is predicted. A local map folded into an earlier one
// (LongTermFolding) stays in its chain and names the node it went into. Owns the chains and the
// paths; the graph, the segments and the folds are the Mapper's, given to each call.
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <unordered_map>

#include "mapping/core/long_term_folding.hpp"
#include "mapping/core/mapper_config.hpp"
#include "mapping/core/pose_graph.hpp"
#include "mapping/core/segments.hpp"

namespace ltm::mapping {

class OdometryChains {
  public:
    using Chain = std::map<std::uint64_t, std::uint64_t>;  // local map id -> graph node

    // What a chain's anchors are read from.
    struct View {
        const PoseGraph& graph;
        const Segments& segments;
        const LongTermFolding& folding;
    };

    // A local map of a chain, folded or not: its anchor as the graph places it.
    struct Anchor {
        std::uint64_t node = 0;
        bool folded = false;
        Eigen::Isometry3d T_node_anchor = Eigen::Isometry3d::Identity();
        Eigen::Isometry3d T_odom_anchor = Eigen::Isometry3d::Identity();
        Eigen::Isometry3d T_world_anchor = Eigen::Isometry3d::Identity();
        std::uint32_t segment = 0;
        double path = 0.0;
        EIGEN_MAKE_ALIGNED_OPERATOR_NEW
    };

    // Every session's chain, by session.
    const std::map<std::uint32_t, Chain>& all() const { return chains_; }
    // A session's chain (nullptr when it has no local map yet).
    const Chain* chain(std::uint32_t session) const;
    bool has(std::uint32_t session) const { return chains_.count(session) > 0; }
    std::optional<std::uint64_t> node_of(std::uint32_t session, std::uint64_t local_map_id) const;
    // Local map `local_map_id` of `session` is node `node` (a loaded one, or where it was folded).
    void set(std::uint32_t session, std::uint64_t local_map_id, std::uint64_t node);
    // A new local map of the chain (a known one keeps its node): its place in the chain.
    Chain::const_iterator insert(std::uint32_t session, std::uint64_t local_map_id,
                                 std::uint64_t node);

    // The odometry path to a node [m] (0 when it has none).
    double path(std::uint64_t node) const;
    bool has_path(std::uint64_t node) const { return path_at_.count(node) > 0; }
    void forget_path(std::uint64_t node) { path_at_.erase(node); }
    // The path to a local map of the chain: the one before it's and the odometry between them.
    void set_path(const View& view, std::uint32_t session, std::uint64_t local_map_id);

    Anchor anchor(const View& view, std::uint32_t session, std::uint64_t local_map_id,
                  std::uint64_t node) const;
    // World pose of a local map's anchor at T_odom_anchor, by the nearest map of the chain
    // (preferably an earlier one): its correction carries over.
    Eigen::Isometry3d predicted_world(const View& view, std::uint32_t session,
                                      std::uint64_t local_map_id,
                                      const Eigen::Isometry3d& T_odom_anchor) const;

    // The odometry edges of a local map of the chain to its neighbours (replacing the one between
    // them), and their removal.
    void link(PoseGraph* graph, const Segments& segments, LongTermFolding* folding,
              const OdometryEdgeConfig& config, std::uint32_t session, std::uint64_t local_map_id);
    void unlink(PoseGraph* graph, const LongTermFolding& folding, std::uint32_t session,
                std::uint64_t local_map_id) const;

    std::size_t memory_bytes() const;

  private:
    std::map<std::uint32_t, Chain> chains_;
    std::unordered_map<std::uint64_t, double> path_at_;  // odometry path to each node [m]
};

}  // namespace ltm::mapping
