// SessionJoins: a loop between two sessions' parts is held until session_join.loops of them, from
// different keyframes, agree; then the agreeing ones go with it and the rest held between the two
// parts is dropped.
#include "mapping/core/session_joins.hpp"

#include <gtest/gtest.h>

#include <utility>

namespace ltm::mapping {
namespace {

struct Fixture {
    PoseGraph graph;
    Segments segments;
    Fixture() {
        for (std::uint32_t s = 0; s < 2; ++s) {
            map::PoseGraphNode n;
            n.id = s;
            n.session = s;
            EXPECT_TRUE(graph.add_node(n));
            segments.set(s, 0, true);
        }
    }
};

map::PoseGraphEdge loop_edge(double x) {
    map::PoseGraphEdge e;
    e.from = 0;
    e.to = 1;
    e.kind = map::EdgeKind::kLoop;
    e.T_from_to = Eigen::Isometry3d(Eigen::Translation3d(x, 0.0, 0.0));
    return e;
}

LoopClosure closure(std::uint32_t query_keyframe) {
    LoopClosure l;
    l.query_session = 1;
    l.query_keyframe = query_keyframe;
    return l;
}

const SegmentKey kFirst(0, 0), kSecond(1, 0);

TEST(SessionJoins, TheFirstLoopIsHeldUntilAnotherKeyframesLoopAgrees) {
    Fixture f;
    SessionJoins joins(SessionJoinConfig{});  // two loops
    std::vector<SessionJoins::Join> agreed;
    EXPECT_FALSE(
        joins.confirm(kFirst, kSecond, loop_edge(1.0), closure(5), f.graph, f.segments, &agreed));
    // The same keyframe again, and a loop that disagrees: held too.
    EXPECT_FALSE(
        joins.confirm(kFirst, kSecond, loop_edge(1.1), closure(5), f.graph, f.segments, &agreed));
    EXPECT_FALSE(
        joins.confirm(kFirst, kSecond, loop_edge(9.0), closure(6), f.graph, f.segments, &agreed));
    EXPECT_TRUE(agreed.empty());
    // Another keyframe's loop that agrees, seen the other way round (from the second session's
    // node): joined with those that agree.
    map::PoseGraphEdge reversed = loop_edge(-1.2);
    std::swap(reversed.from, reversed.to);
    EXPECT_TRUE(joins.confirm(kSecond, kFirst, reversed, closure(7), f.graph, f.segments, &agreed));
    ASSERT_EQ(agreed.size(), 2u);
    EXPECT_EQ(agreed[0].loop.query_keyframe, 5u);
    EXPECT_EQ(agreed[1].loop.query_keyframe, 5u);
    // What was held between the two parts is gone: the next one is held again.
    agreed.clear();
    EXPECT_FALSE(
        joins.confirm(kFirst, kSecond, loop_edge(1.0), closure(8), f.graph, f.segments, &agreed));
}

TEST(SessionJoins, WithOneLoopToJoinNothingIsHeld) {
    Fixture f;
    SessionJoinConfig config;
    config.loops = 1;
    SessionJoins joins(config);
    std::vector<SessionJoins::Join> agreed;
    EXPECT_TRUE(
        joins.confirm(kFirst, kSecond, loop_edge(1.0), closure(5), f.graph, f.segments, &agreed));
    EXPECT_TRUE(agreed.empty());
}

}  // namespace
}  // namespace ltm::mapping
