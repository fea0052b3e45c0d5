// Two robots on one map through the host: the tiny simulated site's two sessions driven at once
// by two simulators, each with its own odometry under /robot1 and /robot2, and one mapping
// component with `robots: [robot1, robot2]`. The saved map is one graph with loops between the
// robots' sessions, each session recorded with its robot; each robot gets its own corrected
// odometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "common/core/trajectory_io.hpp"
#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "map/core/map_store.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kScenario = ltm::tests::scenario("tiny_loop.yaml");

class MultiRobotPipeline : public ltm::tests::TempDirTest {
  protected:
    MultiRobotPipeline() : TempDirTest("ltm_multi_robot_") {}

    // A simulator and an odometry for robot `r` (session `session` of the tiny site), every topic
    // under /r, and a writer of its corrected odometry and of its true poses.
    std::string robot(const std::string& r, int session) const {
        const std::string topics = "{points: /" + r + "/points, odometry: /" + r +
                                   "/odometry, keyframe: /" + r + "/keyframe, local_map: /" + r +
                                   "/local_map, status: /" + r + "/status}";
        return "  - name: sensor_" + r +
               "\n    type: simulator\n    params: {scenario: " + kScenario +
               ", mode: fast, session: " + std::to_string(session) + "}\n    remap: {points: /" +
               r + "/points, ground_truth: /" + r + "/ground_truth}\n  - name: odometry_" + r +
               "\n    type: odometry\n    params: {preset: vlp16, threads: 1}\n    remap: " +
               topics + "\n  - name: corrected_" + r +
               "\n    type: trajectory_writer\n    params: {tum_file: " + path(r + "_slam.txt") +
               ", input: odometry}\n    remap: {odometry: /" + r +
               "/corrected_odometry}\n  - name: truth_" + r +
               "\n    type: trajectory_writer\n    params: {tum_file: " + path(r + "_truth.txt") +
               ", input: pose}\n    remap: {pose: /" + r + "/ground_truth}\n";
    }
};

// Connected parts of a graph (by its edges).
std::size_t components(const map::MapData& map) {
    std::map<std::uint64_t, std::uint64_t> parent;
    for (const map::PoseGraphNode& n : map.nodes) parent[n.id] = n.id;
    auto root = [&](std::uint64_t x) {
        while (parent[x] != x) x = parent[x];
        return x;
    };
    for (const map::PoseGraphEdge& e : map.edges) {
        if (e.active) parent[root(e.from)] = root(e.to);
    }
    std::size_t n = 0;
    for (const auto& [id, up] : parent) n += root(id) == id;
    return n;
}

}  // namespace

TEST_F(MultiRobotPipeline, TwoRobotsAreJoinedIntoOneGraph) {
    const std::string cfg = write("robots.yaml", R"(domain_id: 231
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
topics: {/robot1/points: stream, /robot1/ground_truth: stream, /robot2/points: stream,
         /robot2/ground_truth: stream}
qos: {stream: {max_blocking_s: 2.0}}
components:
)" + robot("robot1", 0) + robot("robot2", 1) +
                                                     R"(  - name: mapping
    type: mapping
    params: {preset: vlp16, robots: [robot1, robot2], map_dir: )" +
                                                     path("map") + R"(, save_period_s: 0}
)");
    Process host({kHost, cfg}, path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();

    const map::LoadedMap loaded = map::load_map(path("map"));
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused[0];
    const map::MapData& map = loaded.map;
    ASSERT_EQ(map.sessions.size(), 2u) << host.err();
    EXPECT_EQ(map.sessions[0].robot, "robot1");
    EXPECT_EQ(map.sessions[1].robot, "robot2");
    std::map<std::uint64_t, std::uint32_t> session_of;
    for (const map::PoseGraphNode& n : map.nodes) session_of[n.id] = n.session;
    std::size_t cross = 0;
    for (const map::PoseGraphEdge& e : map.edges) {
        cross +=
            e.kind == map::EdgeKind::kLoop && e.active && session_of[e.from] != session_of[e.to];
    }
    EXPECT_GE(cross, 1u) << "no loop between the robots\n" << host.err();
    EXPECT_EQ(components(map), 1u) << "not one graph\n" << host.err();
    EXPECT_NE(host.err().find("session 1 (robot2) joined to the map by a loop"), std::string::npos)
        << host.err();

    // Each robot's corrected odometry, on its own topic, a pose a scan; both in the one map frame
    // (robot 1's odometry frame: its first pose there is its first true pose).
    std::map<std::string, common::Trajectory> slam, truth;
    for (const std::string r : {"robot1", "robot2"}) {
        slam[r] = common::read_tum_trajectory(path(r + "_slam.txt"));
        truth[r] = common::read_tum_trajectory(path(r + "_truth.txt"));
        ASSERT_GT(truth[r].size(), 20u) << r;
        ASSERT_EQ(slam[r].size(), truth[r].size()) << r;
    }
    const Eigen::Isometry3d T_world_map =
        truth["robot1"].front().pose * slam["robot1"].front().pose.inverse();
    // Robot 1's last corrected pose where its truth is (its map frame is the map's).
    const Eigen::Vector3d err1 = (T_world_map * slam["robot1"].back().pose).translation() -
                                 truth["robot1"].back().pose.translation();
    EXPECT_LT(err1.norm(), 1.0) << "robot1's last pose off the truth\n" << host.err();
    // The one map: every session's last keyframe joined to it where its robot's truth is. A part
    // of robot 2's path after its kidnap (a new odometry segment) is joined by a loop only once
    // robot 1 has driven there, which may come after both have stopped when the two simulators run
    // as fast as a loaded machine lets them: such a segment must have been reported "not joined"
    // (its poses are the odometry's best estimate across the break, said so) and is not checked.
    std::map<std::uint64_t, const map::PoseGraphNode*> node_of;
    for (const map::PoseGraphNode& n : map.nodes) node_of[n.id] = &n;
    std::map<std::uint64_t, std::uint32_t> segment_of;
    for (const map::StoredLocalMap& m : map.local_maps) {
        if (m.data) segment_of[m.node] = m.data->segment;
    }
    const std::string log = host.err();
    // The segment's last reported state (segment 0: the session's first, joined with it).
    const auto joined = [&](const std::string& r, std::uint32_t segment) {
        if (segment == 0) return true;
        const std::string head = r + ": segment " + std::to_string(segment) + " ";
        const std::size_t at = log.rfind(head);
        if (at == std::string::npos) return false;
        return log.compare(at + head.size(), 6, "joined") == 0;
    };
    for (std::uint32_t session = 0; session < 2; ++session) {
        const std::string r = session == 0 ? "robot1" : "robot2";
        // The odometry restarts (a new segment) after a gap of more than 2 s between scans
        // (tracking.restart_gap): the scans' own stamps say which segment a keyframe is in,
        // whatever local map it went into (a keyframe taken as the segment began can name the
        // local map before it).
        std::vector<double> restarts;
        for (std::size_t i = 1; i < truth[r].size(); ++i) {
            if (truth[r][i].stamp - truth[r][i - 1].stamp > 2.0)
                restarts.push_back(truth[r][i].stamp);
        }
        const map::StoredKeyframe* last = nullptr;
        for (const auto& k : map.keyframes) {
            if (k->session != session || !node_of.count(k->node)) continue;
            std::uint32_t by_time = 0;
            for (const double t : restarts) by_time += k->data.stamp >= t - 1e-6;
            const std::uint32_t segment =
                std::max(segment_of.count(k->node) ? segment_of[k->node] : 0u, by_time);
            if (!joined(r, segment)) {
                EXPECT_NE(log.find(r + ": segment " + std::to_string(segment) + " (from local map"),
                          std::string::npos)
                    << r << "'s segment " << segment << " neither joined nor said not to be\n"
                    << log;
                continue;
            }
            if (!last || k->data.stamp > last->data.stamp) last = k.get();
        }
        ASSERT_NE(last, nullptr) << r;
        const Eigen::Isometry3d T_map_lidar =
            node_of[last->node]->T_world_anchor * last->data.T_anchor_lidar;
        const auto t = std::find_if(truth[r].begin(), truth[r].end(), [&](const auto& p) {
            return std::abs(p.stamp - last->data.stamp) < 1e-4;
        });
        ASSERT_NE(t, truth[r].end()) << r << " keyframe at " << last->data.stamp;
        const Eigen::Vector3d err =
            (T_world_map * T_map_lidar).translation() - t->pose.translation();
        EXPECT_LT(err.norm(), 1.0) << r << "'s last keyframe off the truth\n" << host.err();
    }
}
