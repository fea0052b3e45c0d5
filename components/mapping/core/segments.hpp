#pragma once
// The odometry segments of the Mapper's graph nodes (mapper.hpp) and the parts of the map that
// loops have placed together. A node's segment is told by its local map (or a loaded map's
// breaks); until then it takes the segment of the map before it. After an optimisation, the
// active loop edges (and the odometry edges that are not breaks) join (session, segment) keys
// into placed parts, each named by its root. Owns the segments and the placement; reads the graph
// it is given.
#include <cstddef>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <utility>

#include "mapping/core/pose_graph.hpp"

namespace ltm::mapping {

// An odometry segment of a session: (session, segment).
using SegmentKey = std::pair<std::uint32_t, std::uint32_t>;

class Segments {
  public:
    // The node's segment (0 for an unknown node).
    std::uint32_t of(std::uint64_t node) const;
    // The node's segment is known (its local map said it, or it came with a loaded map), or the
    // node is unknown.
    bool known(std::uint64_t node) const;
    // Sets the node's segment, `told` by its local map or taken from the map before it.
    void set(std::uint64_t node, std::uint32_t segment, bool told);
    // The node's local map says its segment: true when that changed it.
    bool tell(std::uint64_t node, std::uint32_t segment);
    // The node takes `segment` from the map before it, unless its own local map told it one:
    // false then (nothing changed).
    bool follow(std::uint64_t node, std::uint32_t segment);
    void forget(std::uint64_t node);

    // The node's (session, segment).
    SegmentKey key(const PoseGraph& graph, std::uint64_t node) const;
    // The part a segment is placed in, as of the last update_placement().
    SegmentKey root(const SegmentKey& key) const;
    SegmentKey root(const PoseGraph& graph, std::uint64_t node) const {
        return root(key(graph, node));
    }
    // Joined segments from the graph's active loop edges, after an optimisation.
    void update_placement(const PoseGraph& graph);
    // The graph's parts that loops have placed together.
    std::size_t placed_parts(const PoseGraph& graph) const;

  private:
    struct NodeSegment {
        std::uint32_t segment = 0;
        bool told = false;  // by the node's local map (else taken from the map before it)
    };

    std::unordered_map<std::uint64_t, NodeSegment> of_;  // by node
    // Segments placed together by active loops, as of the last update: key -> its root.
    std::map<SegmentKey, SegmentKey> placed_;
};

}  // namespace ltm::mapping
