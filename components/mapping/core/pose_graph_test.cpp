#include "mapping/core/pose_graph.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ltm::mapping {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d pose(double x, double y, double z, double yaw_deg, double roll_deg = 0.0) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, z);
    return T;
}

Eigen::Isometry3d noisy(const Eigen::Isometry3d& T, std::mt19937& rng, double sigma_t,
                        double sigma_r_deg) {
    std::normal_distribution<double> n(0.0, 1.0);
    Eigen::Isometry3d N = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d r(n(rng), n(rng), n(rng));
    N.linear() =
        Eigen::AngleAxisd(sigma_r_deg * kDeg * r.norm(), r.normalized()).toRotationMatrix();
    N.translation() = sigma_t * Eigen::Vector3d(n(rng), n(rng), n(rng));
    return T * N;
}

Matrix6d information(double sigma_t, double sigma_r_deg) {
    Matrix6d I = Matrix6d::Zero();
    I.diagonal().head<3>().setConstant(1.0 / (sigma_t * sigma_t));
    I.diagonal().tail<3>().setConstant(1.0 / std::pow(sigma_r_deg * kDeg, 2));
    return I;
}

// A 40-anchor loop around a 100 x 100 m block (with some height and roll), its drifting
// odometry, true loop edges where the path comes back, and one false loop.
struct Scenario {
    std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> truth;
    PoseGraph graph;
};

Scenario make_scenario(const PoseGraphConfig& config, bool with_false_loop) {
    Scenario s{{}, PoseGraph(config)};
    for (int i = 0; i < 40; ++i) {
        const int side = i / 10, k = i % 10;
        const double a = 10.0 * k;
        const double x = side == 0 ? a : side == 1 ? 100 : side == 2 ? 100 - a : 0;
        const double y = side == 0 ? 0 : side == 1 ? a : side == 2 ? 100 : 100 - a;
        s.truth.push_back(pose(x, y, 0.05 * i, 90.0 * side + 2.0 * k, 1.0 * std::sin(i)));
    }
    std::mt19937 rng(42);
    Eigen::Isometry3d odom = s.truth[0];
    for (std::size_t i = 0; i < s.truth.size(); ++i) {
        if (i > 0) {
            const Eigen::Isometry3d Z =
                noisy(s.truth[i - 1].inverse() * s.truth[i], rng, 0.05, 0.4);
            odom = odom * Z;
            map::PoseGraphNode n;
            n.id = 100 + i;
            n.T_odom_anchor = n.T_world_anchor = odom;
            EXPECT_TRUE(s.graph.add_node(n));
            map::PoseGraphEdge e;
            e.from = 100 + i - 1;
            e.to = 100 + i;
            e.T_from_to = Z;
            e.information = information(0.05, 0.4);
            EXPECT_TRUE(s.graph.add_edge(e));
        } else {
            map::PoseGraphNode n;
            n.id = 100;
            n.T_odom_anchor = n.T_world_anchor = odom;
            EXPECT_TRUE(s.graph.add_node(n));
        }
    }
    // True loops: the last anchors see the first ones again.
    for (const auto& [a, b] :
         std::vector<std::pair<int, int>>{{0, 39}, {1, 39}, {0, 38}, {2, 38}}) {
        map::PoseGraphEdge e;
        e.kind = map::EdgeKind::kLoop;
        e.from = 100 + a;
        e.to = 100 + b;
        e.T_from_to = noisy(s.truth[a].inverse() * s.truth[b], rng, 0.02, 0.1);
        e.information = information(0.05, 0.2);
        EXPECT_TRUE(s.graph.add_edge(e));
    }
    if (with_false_loop) {
        // Anchor 25 "recognised" as anchor 5 (the other side of the block): a wrong place.
        map::PoseGraphEdge e;
        e.kind = map::EdgeKind::kLoop;
        e.from = 105;
        e.to = 125;
        e.T_from_to = pose(3.0, 1.0, 0.0, 175.0);
        e.information = information(0.05, 0.2);
        e.query_keyframe = 7;
        EXPECT_TRUE(s.graph.add_edge(e));
    }
    return s;
}

double max_position_error(const Scenario& s) {
    double worst = 0.0;
    for (std::size_t i = 0; i < s.truth.size(); ++i) {
        const map::PoseGraphNode* n = s.graph.find(100 + i);
        worst =
            std::max(worst, (n->T_world_anchor.translation() - s.truth[i].translation()).norm());
    }
    return worst;
}

double max_difference(const Scenario& a, const Scenario& b) {
    double worst = 0.0;
    for (const map::PoseGraphNode& n : a.graph.nodes()) {
        const Eigen::Isometry3d d = n.T_world_anchor.inverse() * b.graph.find(n.id)->T_world_anchor;
        worst =
            std::max({worst, d.translation().norm(), Eigen::AngleAxisd(d.linear()).angle() * 10.0});
    }
    return worst;
}

// The oracle: the same optimisation of the graph without the false loop.
Scenario clean_solution(const PoseGraphConfig& config) {
    Scenario clean = make_scenario(config, false);
    EXPECT_TRUE(clean.graph.optimise().solved);
    return clean;
}

TEST(PoseGraph, RecoversKnownAnchorsAndRejectsAFalseLoop) {
    const Scenario clean = clean_solution(PoseGraphConfig());
    Scenario s = make_scenario(PoseGraphConfig(), true);
    const double drift = max_position_error(s);
    EXPECT_GT(drift, 3.0) << "the odometry alone must be visibly wrong for the test to mean much";
    const OptimisationSummary r = s.graph.optimise();
    ASSERT_TRUE(r.solved) << r.message;
    EXPECT_EQ(r.loops_rejected, 1u);
    EXPECT_EQ(r.loops_active, 4u);
    EXPECT_EQ(r.components, 1u);
    EXPECT_GE(r.solves, 2);
    for (const map::PoseGraphEdge& e : s.graph.edges()) {
        if (e.kind != map::EdgeKind::kLoop) continue;
        EXPECT_EQ(e.active, e.query_keyframe != 7) << e.from << " -> " << e.to;
        if (e.active) {
            EXPECT_LT(e.error_translation, 0.2);
        }
    }
    // The same anchors as without the false loop, and far closer to the truth than the odometry.
    EXPECT_LT(max_difference(s, clean), 1e-2);
    EXPECT_LT(max_position_error(s), drift / 2.0) << "odometry drift was " << drift;
    // The first anchor held the gauge.
    EXPECT_LT((s.graph.find(100)->T_world_anchor.translation() - s.truth[0].translation()).norm(),
              1e-9);
}

TEST(PoseGraph, WithoutRobustnessTheFalseLoopCorruptsTheGraph) {
    // The counter-check of the previous test: plain least squares keeps the false loop.
    PoseGraphConfig plain;
    plain.loop_loss = "none";
    plain.max_outlier_rounds = 0;
    const Scenario clean = clean_solution(plain);
    Scenario s = make_scenario(plain, true);
    ASSERT_TRUE(s.graph.optimise().solved);
    EXPECT_GT(max_difference(s, clean), 1.0);
}

TEST(PoseGraph, ExactEdgesGiveTheExactPoses) {
    PoseGraph g{PoseGraphConfig()};
    const std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> truth = {
        pose(0, 0, 0, 0), pose(5, 1, 0.2, 30, 3), pose(9, 6, 0.1, 80, -2), pose(4, 9, 0, 170)};
    for (std::size_t i = 0; i < truth.size(); ++i) {
        map::PoseGraphNode n;
        n.id = i;
        n.T_world_anchor = i == 0 ? truth[0] : pose(1.0 * i, 0, 0, 0);  // a poor start
        ASSERT_TRUE(g.add_node(n));
    }
    for (std::size_t i = 0; i < truth.size(); ++i) {
        for (std::size_t j = i + 1; j < truth.size(); ++j) {
            map::PoseGraphEdge e;
            e.from = i;
            e.to = j;
            e.kind = j == i + 1 ? map::EdgeKind::kOdometry : map::EdgeKind::kLoop;
            e.T_from_to = truth[i].inverse() * truth[j];
            ASSERT_TRUE(g.add_edge(e));
        }
    }
    const OptimisationSummary r = g.optimise();
    ASSERT_TRUE(r.solved) << r.message;
    EXPECT_EQ(r.loops_rejected, 0u);
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const Eigen::Isometry3d d = truth[i].inverse() * g.find(i)->T_world_anchor;
        EXPECT_LT(d.translation().norm(), 1e-6) << i;
        EXPECT_LT(Eigen::AngleAxisd(d.linear()).angle(), 1e-6) << i;
    }
    EXPECT_LT(r.final_cost, 1e-12);
}

TEST(PoseGraph, EachDisconnectedPartKeepsItsGauge) {
    PoseGraph g{PoseGraphConfig()};
    for (std::uint64_t id : {1, 2, 10, 11}) {
        map::PoseGraphNode n;
        n.id = id;
        n.T_world_anchor = pose(double(id), 0, 0, 0);
        ASSERT_TRUE(g.add_node(n));
    }
    map::PoseGraphEdge e;
    e.from = 1;
    e.to = 2;
    e.T_from_to = pose(2, 0, 0, 0);
    ASSERT_TRUE(g.add_edge(e));
    e.from = 10;
    e.to = 11;
    ASSERT_TRUE(g.add_edge(e));
    ASSERT_TRUE(g.set_fixed(11, true));
    const OptimisationSummary r = g.optimise();
    ASSERT_TRUE(r.solved) << r.message;
    EXPECT_EQ(r.components, 2u);
    EXPECT_NEAR(g.find(1)->T_world_anchor.translation().x(), 1.0, 1e-9);  // first node held
    EXPECT_NEAR(g.find(2)->T_world_anchor.translation().x(), 3.0, 1e-6);
    EXPECT_NEAR(g.find(11)->T_world_anchor.translation().x(), 11.0, 1e-9);  // fixed node held
    EXPECT_NEAR(g.find(10)->T_world_anchor.translation().x(), 9.0, 1e-6);
}

TEST(PoseGraph, RefusesBadNodesAndEdges) {
    PoseGraph g{PoseGraphConfig()};
    map::PoseGraphNode n;
    n.id = 1;
    ASSERT_TRUE(g.add_node(n));
    EXPECT_FALSE(g.add_node(n));  // same id
    n.id = 2;
    n.T_world_anchor.translation().x() = std::nan("");
    EXPECT_FALSE(g.add_node(n));
    map::PoseGraphEdge e;
    e.from = 1;
    e.to = 3;
    EXPECT_FALSE(g.add_edge(e));  // no node 3
    e.to = 1;
    EXPECT_FALSE(g.add_edge(e));       // a self loop
    EXPECT_TRUE(g.optimise().solved);  // nothing to do is not an error
}

TEST(PoseGraph, ValidateNamesTheKey) {
    PoseGraphConfig c;
    c.loop_loss = "tukey";
    ASSERT_TRUE(validate(c));
    EXPECT_EQ(validate(c)->key, "loop_loss");
    EXPECT_EQ(validate(c)->problem, "must be cauchy, huber or none (got 'tukey')");
    EXPECT_THROW(PoseGraph{c}, common::ConfigError);
    EXPECT_FALSE(validate(PoseGraphConfig()));
}

}  // namespace
}  // namespace ltm::mapping
