// Segments: what a node's segment is told or takes from the map before it, and the parts that
// active loop edges (and odometry edges that are not breaks) place together.
#include "mapping/core/segments.hpp"

#include <gtest/gtest.h>

#include "mapping/core/mapper_config.hpp"

namespace ltm::mapping {
namespace {

map::PoseGraphNode node(std::uint64_t id, std::uint32_t session) {
    map::PoseGraphNode n;
    n.id = id;
    n.session = session;
    n.local_map_id = id;
    return n;
}

map::PoseGraphEdge edge(std::uint64_t from, std::uint64_t to, map::EdgeKind kind) {
    map::PoseGraphEdge e;
    e.from = from;
    e.to = to;
    e.kind = kind;
    e.active = true;
    e.information = kind == map::EdgeKind::kOdometry ? segment_break_information()
                                                     : Matrix6d::Identity().eval();
    return e;
}

TEST(Segments, ASegmentTakenFromTheMapBeforeGivesWayToTheOneItsLocalMapTells) {
    Segments s;
    EXPECT_EQ(s.of(7), 0u);
    EXPECT_TRUE(s.known(7));  // an unknown node
    s.set(1, 0, false);
    EXPECT_FALSE(s.known(1));
    EXPECT_TRUE(s.follow(1, 2));
    EXPECT_EQ(s.of(1), 2u);
    EXPECT_TRUE(s.tell(1, 3));
    EXPECT_TRUE(s.known(1));
    EXPECT_FALSE(s.follow(1, 5));  // told: it keeps its own
    EXPECT_EQ(s.of(1), 3u);
    EXPECT_FALSE(s.tell(1, 3));  // unchanged
    s.forget(1);
    EXPECT_EQ(s.of(1), 0u);
}

TEST(Segments, ActiveLoopsPlaceSegmentsTogetherAndABreakDoesNot) {
    PoseGraph graph;
    ASSERT_TRUE(graph.add_node(node(0, 0)));
    ASSERT_TRUE(graph.add_node(node(1, 0)));
    ASSERT_TRUE(graph.add_node(node(2, 1)));
    Segments s;
    s.set(0, 0, true);
    s.set(1, 1, true);
    s.set(2, 0, true);
    ASSERT_TRUE(graph.add_edge(edge(0, 1, map::EdgeKind::kOdometry)));  // a segment break
    ASSERT_TRUE(graph.add_edge(edge(1, 2, map::EdgeKind::kLoop)));
    s.update_placement(graph);
    EXPECT_EQ(s.key(graph, 2), SegmentKey(1, 0));
    EXPECT_EQ(s.root(graph, 2), SegmentKey(0, 1));  // the lower key names the part
    EXPECT_EQ(s.root(graph, 0), SegmentKey(0, 0));
    EXPECT_EQ(s.placed_parts(graph), 2u);

    map::PoseGraphEdge inactive = edge(0, 2, map::EdgeKind::kLoop);
    inactive.active = false;
    ASSERT_TRUE(graph.add_edge(inactive));
    s.update_placement(graph);
    EXPECT_EQ(s.placed_parts(graph), 2u);

    ASSERT_TRUE(graph.add_edge(edge(0, 2, map::EdgeKind::kLoop)));
    s.update_placement(graph);
    EXPECT_EQ(s.placed_parts(graph), 1u);
    EXPECT_EQ(s.root(graph, 1), SegmentKey(0, 0));
    EXPECT_EQ(s.root(graph, 2), SegmentKey(0, 0));
}

}  // namespace
}  // namespace ltm::mapping
