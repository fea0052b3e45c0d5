#pragma once
// The graph of local-map anchors (METHOD.md Eq. 10): nodes are anchor poses, edges relative anchor
// poses (odometry edges between consecutive maps, loop edges from verified loop closures), and
// its optimisation with Ceres on demand (SE(3): a translation and a quaternion on
// ceres::EigenQuaternionManifold, a robust loss on loop edges). After a solve, loop edges whose
// residual is still large are outliers: disabled, and the graph is solved again without them.
// Every optimise() re-examines all loop edges, from the current estimate.
//
// Edge error, in the measurement's frame: E = Z^-1 * (T_world_from^-1 * T_world_to), as
// e = [t(E); 2 vec(q(E))] (translation first, as the odometry's covariances), weighted by the
// edge's 6x6 information.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/core/config_check.hpp"
#include "map/core/map_graph.hpp"

namespace ltm::mapping {

using Matrix6d = map::Matrix6d;

struct PoseGraphConfig {
    std::string loop_loss = "cauchy";  // robust loss of loop edges: "cauchy", "huber" or "none"
    double loop_loss_scale = 3.0;      // of the whitened residual norm (quadratic below)
    int max_iterations = 100;          // Levenberg-Marquardt iterations a solve
    // After a solve, a loop edge with a larger error is an outlier (disabled, solved again).
    double outlier_translation = 1.0;  // [m]
    double outlier_rotation = 5.0;     // [deg]
    int max_outlier_rounds = 3;        // solves after the first one, while outliers are found
};

// Calls v(key, field, rule) for every field, keys under `prefix` ("pose_graph."); the rule is the
// field's (common/core/config_check.hpp). An infinite outlier bound rejects no loop.
template <class Visitor>
void visit_fields(PoseGraphConfig& c, const std::string& prefix, Visitor&& v) {
    using namespace common::rules;
    v(prefix + "loop_loss", c.loop_loss, one_of({"cauchy", "huber", "none"}));
    v(prefix + "loop_loss_scale", c.loop_loss_scale, positive.or_infinite());
    v(prefix + "max_iterations", c.max_iterations, at_least(1));
    v(prefix + "outlier_translation", c.outlier_translation, positive.or_infinite());
    v(prefix + "outlier_rotation", c.outlier_rotation, positive.or_infinite());
    v(prefix + "max_outlier_rounds", c.max_outlier_rounds, non_negative);
}

// The first field that breaks its rule (key relative: "loop_loss"); nullopt when valid.
std::optional<common::ConfigProblem> validate(const PoseGraphConfig& config);

struct OptimisationSummary {
    bool solved = false;  // Ceres reported a usable solution
    std::string message;  // Ceres' report, or why nothing was solved
    int iterations = 0;   // over all solves
    int solves = 0;
    double initial_cost = 0.0, final_cost = 0.0;  // of the first and the last solve
    std::size_t nodes = 0, edges = 0, loops_active = 0, loops_rejected = 0;
    std::size_t components = 0;  // connected parts (each has one node held fixed)
};

class PoseGraph {
  public:
    PoseGraph() = default;
    // Throws std::invalid_argument (naming the key) on an invalid configuration.
    explicit PoseGraph(const PoseGraphConfig& config);

    const PoseGraphConfig& config() const { return config_; }
    const std::vector<map::PoseGraphNode>& nodes() const { return nodes_; }
    const std::vector<map::PoseGraphEdge>& edges() const { return edges_; }
    // Null when there is no such node.
    const map::PoseGraphNode* find(std::uint64_t id) const;

    // False (nothing added) when the id exists or a pose is not finite.
    bool add_node(const map::PoseGraphNode& node);
    // False when a node is missing, the nodes are the same, or a value is not finite.
    bool add_edge(const map::PoseGraphEdge& edge);
    // Removes the edges (from, to) of this kind; false when there is none.
    bool remove_edges(std::uint64_t from, std::uint64_t to, map::EdgeKind kind);
    bool set_pose(std::uint64_t id, const Eigen::Isometry3d& T_world_anchor);
    bool set_fixed(std::uint64_t id, bool fixed);

    // Solves from the current estimate; on success the nodes hold the optimum and the loop edges
    // their errors and active flags. Never throws: the summary says what happened.
    OptimisationSummary optimise();

  private:
    OptimisationSummary solve_once(const std::vector<char>& hold);
    void update_errors();

    PoseGraphConfig config_;
    std::vector<map::PoseGraphNode> nodes_;
    std::vector<map::PoseGraphEdge> edges_;
    std::unordered_map<std::uint64_t, std::size_t> index_;  // node id -> nodes_ index
};

}  // namespace ltm::mapping
