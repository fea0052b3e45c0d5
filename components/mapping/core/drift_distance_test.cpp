#include "mapping/core/drift_distance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace ltm::mapping {
namespace {

// A chain of `n` nodes 10 m apart (node i at x = 10 i).
PoseGraph chain(int n) {
    PoseGraph g;
    for (int i = 0; i < n; ++i) {
        map::PoseGraphNode node;
        node.id = std::uint64_t(i);
        node.local_map_id = std::uint64_t(i);
        node.T_world_anchor.translation().x() = 10.0 * i;
        EXPECT_TRUE(g.add_node(node));
        if (i > 0) {
            map::PoseGraphEdge e;
            e.from = std::uint64_t(i - 1);
            e.to = std::uint64_t(i);
            e.T_from_to.translation().x() = 10.0;
            EXPECT_TRUE(g.add_edge(e));
        }
    }
    return g;
}

double length(const map::PoseGraphEdge& e) { return e.T_from_to.translation().norm(); }

map::PoseGraphEdge loop(std::uint64_t from, std::uint64_t to) {
    map::PoseGraphEdge e;
    e.from = from;
    e.to = to;
    e.kind = map::EdgeKind::kLoop;
    return e;
}

TEST(DriftDistance, OdometryPathThenShortcutsThroughLoops) {
    PoseGraph g = chain(50);
    EXPECT_DOUBLE_EQ(drift_distance(g, 3, 3, length), 0.0);
    EXPECT_DOUBLE_EQ(drift_distance(g, 2, 40, length), 380.0);
    EXPECT_DOUBLE_EQ(drift_distance(g, 40, 2, length), 380.0);
    // A loop joins 5 and 45: 2 -> 5 (30 m), loop (0), 45 -> 40 (50 m).
    ASSERT_TRUE(g.add_edge(loop(5, 45)));
    EXPECT_DOUBLE_EQ(drift_distance(g, 2, 40, length), 80.0);
    EXPECT_DOUBLE_EQ(drift_distance(g, 20, 25, length), 50.0);  // the chain is shorter here
}

TEST(DriftDistance, DisabledLoopsAreNotUsedAndDisconnectedIsInfinite) {
    PoseGraph g = chain(10);
    map::PoseGraphEdge disabled = loop(0, 9);
    disabled.active = false;
    ASSERT_TRUE(g.add_edge(disabled));
    EXPECT_DOUBLE_EQ(drift_distance(g, 0, 9, length), 90.0);
    map::PoseGraphNode lonely;
    lonely.id = 100;
    ASSERT_TRUE(g.add_node(lonely));
    EXPECT_TRUE(std::isinf(drift_distance(g, 0, 100, length)));
}

TEST(DriftDistance, AnEdgeOfInfiniteLengthIsNoPathButALoopAroundItIs) {
    PoseGraph g = chain(10);
    // The odometry lost track between 4 and 5: that edge bounds nothing.
    auto broken = [](const map::PoseGraphEdge& e) {
        return e.from == 4 ? std::numeric_limits<double>::infinity() : length(e);
    };
    EXPECT_TRUE(std::isinf(drift_distance(g, 2, 7, broken)));
    EXPECT_DOUBLE_EQ(drift_distance(g, 5, 9, broken), 40.0);
    ASSERT_TRUE(g.add_edge(loop(3, 6)));  // a loop joins the two sides
    EXPECT_DOUBLE_EQ(drift_distance(g, 2, 7, broken), 20.0);
}

TEST(DriftDistance, MatchesABruteForceOracleOnRandomGraphs) {
    std::mt19937 rng(11);
    for (int round = 0; round < 20; ++round) {
        const int n = 30;
        PoseGraph g = chain(n);
        std::uniform_int_distribution<int> pick(0, n - 1);
        for (int k = 0; k < 6; ++k) {
            const int a = pick(rng), b = pick(rng);
            if (a != b) g.add_edge(loop(std::uint64_t(a), std::uint64_t(b)));
        }
        // Floyd-Warshall over the same weights.
        std::vector<std::vector<double>> d(n, std::vector<double>(n, INFINITY));
        for (int i = 0; i < n; ++i) d[i][i] = 0.0;
        for (const map::PoseGraphEdge& e : g.edges()) {
            const double w = e.kind == map::EdgeKind::kLoop ? 0.0 : length(e);
            d[e.from][e.to] = std::min(d[e.from][e.to], w);
            d[e.to][e.from] = std::min(d[e.to][e.from], w);
        }
        for (int k = 0; k < n; ++k)
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) d[i][j] = std::min(d[i][j], d[i][k] + d[k][j]);
        for (int k = 0; k < 20; ++k) {
            const int a = pick(rng), b = pick(rng);
            EXPECT_DOUBLE_EQ(drift_distance(g, std::uint64_t(a), std::uint64_t(b), length),
                             d[a][b]);
        }
    }
}

}  // namespace
}  // namespace ltm::mapping
