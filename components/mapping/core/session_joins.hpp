#pragma once
// Loops between two open sessions' parts that no loop placed together yet (SessionJoinConfig,
// mapper.hpp): a repetitive site can fool one verification, so the first ones are held until
// session_join.loops of them agree. Owns the held loops; reads the graph it is given.
#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

#include "map/core/map_data.hpp"
#include "mapping/core/mapper_config.hpp"
#include "mapping/core/mapper_results.hpp"
#include "mapping/core/pose_graph.hpp"
#include "mapping/core/segments.hpp"

namespace ltm::mapping {

class SessionJoins {
  public:
    // A loop edge and its closure.
    struct Join {
        map::PoseGraphEdge edge;
        LoopClosure loop;
        EIGEN_MAKE_ALIGNED_OPERATOR_NEW
    };

    explicit SessionJoins(const SessionJoinConfig& config) : config_(config) {}

    // A loop between the parts `match_root` and `query_root` (no loop placed them together): true
    // when it is to be added now, with the held loops that agree with it appended to `agreed` (to
    // be added before it, in order; what else was held between the two parts is dropped); false
    // when it is held.
    bool confirm(const SegmentKey& match_root, const SegmentKey& query_root,
                 const map::PoseGraphEdge& edge, const LoopClosure& loop, const PoseGraph& graph,
                 const Segments& segments, std::vector<Join>* agreed);

  private:
    struct Held {
        SegmentKey match_root, query_root;
        Join join;
    };

    SessionJoinConfig config_;
    std::vector<Held> held_;
};

}  // namespace ltm::mapping
