#include "slam/bench/graph_bench.hpp"

#include <chrono>
#include <cmath>
#include <random>

#include "mapping/core/pose_graph.hpp"

namespace ltm::slam::bench {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr int kLap = 50;  // anchors a lap: 4 sides of 250 m

Eigen::Isometry3d lap_pose(std::size_t i) {
    const int k = int(i % kLap), side = k / 12, s = k % 12;  // 48 on the sides, 2 to close
    const double a = std::min(250.0, 20.8 * s);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    const double x = side == 0 ? a : side == 1 ? 250 : side == 2 ? 250 - a : 0;
    const double y = side == 0 ? 0 : side == 1 ? a : side == 2 ? 250 : 250 - a;
    T.translation() = Eigen::Vector3d(x + 0.5 * double(i / kLap), y, 0.01 * double(k));
    T.linear() =
        Eigen::AngleAxisd(side * M_PI / 2 + 0.01 * s, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
}

Eigen::Isometry3d noisy(const Eigen::Isometry3d& T, std::mt19937& rng, double st, double sr_deg) {
    std::normal_distribution<double> n(0.0, 1.0);
    Eigen::Isometry3d N = Eigen::Isometry3d::Identity();
    const Eigen::Vector3d r(n(rng), n(rng), n(rng));
    N.linear() = Eigen::AngleAxisd(sr_deg * kDeg * r.norm(), r.normalized()).toRotationMatrix();
    N.translation() = st * Eigen::Vector3d(n(rng), n(rng), n(rng));
    return T * N;
}

}  // namespace

GraphBenchResult run_graph_bench(std::size_t anchors, const mapping::MapperConfig& config,
                                 std::uint32_t seed) {
    GraphBenchResult out;
    std::mt19937 rng(seed);
    mapping::PoseGraph graph(config.pose_graph);
    std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> truth;
    Eigen::Isometry3d odom = lap_pose(0);
    for (std::size_t i = 0; i < anchors; ++i) {
        truth.push_back(lap_pose(i));
        map::PoseGraphNode n;
        n.id = i;
        n.local_map_id = i;
        if (i > 0) {
            const Eigen::Isometry3d Z = noisy(truth[i - 1].inverse() * truth[i], rng, 0.05, 0.05);
            odom = odom * Z;
            map::PoseGraphEdge e;
            e.from = i - 1;
            e.to = i;
            e.T_from_to = Z;
            e.information = odometry_information(config.odometry_edge, Z.translation().norm());
            n.T_odom_anchor = n.T_world_anchor = odom;
            graph.add_node(n);
            graph.add_edge(e);
        } else {
            n.T_odom_anchor = n.T_world_anchor = odom;
            graph.add_node(n);
        }
    }
    auto add_loop = [&](std::size_t q) {
        map::PoseGraphEdge e;
        e.kind = map::EdgeKind::kLoop;
        e.from = q % kLap;
        e.to = q;
        e.T_from_to = noisy(truth[e.from].inverse() * truth[q], rng, 0.05, 0.1);
        e.information = loop_information(config.loop_edge);
        e.query_keyframe = q;
        graph.add_edge(e);
        ++out.loops;
    };
    for (std::size_t q = kLap; q + 1 < anchors; q += 2) add_loop(q);
    auto worst = [&]() {
        double w = 0.0;
        for (std::size_t i = 0; i < anchors; ++i) {
            w = std::max(
                w, (graph.find(i)->T_world_anchor.translation() - truth[i].translation()).norm());
        }
        return w;
    };
    out.error_before = worst();
    using Clock = std::chrono::steady_clock;
    auto t0 = Clock::now();
    mapping::OptimisationSummary s = graph.optimise();
    out.first_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    out.iterations = s.iterations;
    out.solves = s.solves;
    if (anchors > kLap) add_loop(anchors - 1);
    t0 = Clock::now();
    s = graph.optimise();
    out.incremental_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    out.solved = s.solved;
    out.loops_rejected = s.loops_rejected;
    out.error_after = worst();
    out.nodes = graph.nodes().size();
    out.edges = graph.edges().size();
    return out;
}

}  // namespace ltm::slam::bench
