// The lifelong mode through the host (issue 26): launch_configs/robot_lifelong.yaml, the same
// config every day, on tiny_week's three days. Monday maps a new site; Tuesday localises on
// Monday's version, drives new ground and sees a parked vehicle gone; Wednesday starts, kidnapped,
// on Tuesday's new ground. Checked: each day ends as the site's next version (listed, intact);
// Tuesday's version has the new ground and not the vehicle that left; Wednesday is localised on
// the new ground from its first scans; the old keyframes stay where they were.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "common/core/trajectory_io.hpp"
#include "evaluation/core/alignment.hpp"
#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/stamped_poses.hpp"
#include "host/temp_dir_test.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_store.hpp"
#include "simulator/core/objects.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kConfig = std::string(LTM_SOURCE_DIR) + "/launch_configs/robot_lifelong.yaml";
const std::string kScenario = ltm::tests::scenario("tiny_week.yaml");

class LifelongPipeline : public ltm::tests::TempDirTest {
  protected:
    LifelongPipeline() : TempDirTest("ltm_lifelong_") {}

    // One day through the host; its exit status.
    int day(int session, std::string* log) {
        const std::string out = path("day" + std::to_string(session));
        setenv("LTM_SITE", path("site").c_str(), 1);
        setenv("LTM_SCENARIO", kScenario.c_str(), 1);
        setenv("LTM_OUT", out.c_str(), 1);
        Process host({kHost, kConfig, "--set", "domain_id=231", "--set",
                      "dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}", "--set",
                      "odometry.preset=vlp16", "--set", "localisation.preset=vlp16", "--set",
                      "mapping.preset=vlp16", "--set", "sensor.session=" + std::to_string(session)},
                     out + "_host");
        const int status = host.wait(600);
        *log = host.err();
        return status;
    }

    // Monday's SLAM keyframes (map frame) against the truth (world): the map-to-world alignment.
    Eigen::Isometry3d map_to_world() {
        return tests::map_to_world(path("day0/slam_tum.txt"), path("day0/ground_truth_tum.txt"));
    }

    // World positions of a saved map's voxels.
    static std::vector<Eigen::Vector3d> voxels(const std::string& map_dir,
                                               const Eigen::Isometry3d& T_world_map) {
        std::vector<Eigen::Vector3d> out;
        const map::LoadedMap loaded = map::load_map(map_dir);
        for (const map::StoredLocalMap& m : loaded.map.local_maps) {
            const map::PoseGraphNode* n = nullptr;
            for (const map::PoseGraphNode& g : loaded.map.nodes)
                if (g.id == m.node) n = &g;
            if (!n) continue;
            const Eigen::Isometry3d T = T_world_map * n->T_world_anchor * m.data->T_anchor_grid;
            for (const common::VoxelData& v : m.data->voxels)
                out.push_back(T * v.centre.cast<double>());
        }
        return out;
    }
};

TEST_F(LifelongPipeline, ThreeDaysOnOneConfigGrowTheMapLearnItsChangesAndLocaliseOnTheNewGround) {
    std::string log;
    ASSERT_EQ(day(0, &log), 0) << log;
    ASSERT_NE(log.find("new site"), std::string::npos) << log;
    ASSERT_EQ(day(1, &log), 0) << log;
    EXPECT_NE(log.find("placed on the loaded map by the localisation"), std::string::npos) << log;
    ASSERT_EQ(day(2, &log), 0) << log;

    // Three versions, intact, the newest last.
    const std::vector<map::SiteVersion> versions = map::SiteStore(path("site")).versions();
    ASSERT_EQ(versions.size(), 3u);
    for (const map::SiteVersion& v : versions) EXPECT_TRUE(v.intact) << v.name << ": " << v.problem;
    const Eigen::Isometry3d T_world_map = map_to_world();
    // Monday, a new site: the SLAM's pose of every scan was the map pose.
    EXPECT_GE(tests::poses_by_stamp_ms(path("day0/localisation_tum.txt")).size(),
              tests::poses_by_stamp_ms(path("day0/ground_truth_tum.txt")).size() * 9 / 10);

    // Tuesday's new ground (x > 30 m, where Monday never drove) has keyframes in Tuesday's version.
    auto keyframes_east = [&](const map::SiteVersion& v) {
        const map::LoadedMap m = map::load_map(v.map_dir());
        std::size_t east = 0;
        for (const auto& k : m.map.keyframes) {
            for (const map::PoseGraphNode& n : m.map.nodes) {
                if (n.id != k->node) continue;
                east +=
                    (T_world_map * n.T_world_anchor * k->data.T_anchor_lidar).translation().x() >
                    30.0;
            }
        }
        return east;
    };
    EXPECT_EQ(keyframes_east(versions[0]), 0u);
    EXPECT_GE(keyframes_east(versions[1]), 5u);

    // The parked vehicle gone on Tuesday: in Monday's version, (nearly) not in Tuesday's.
    const sim::Simulator tuesday(sim::load_scenario(kScenario), 1);
    std::optional<sim::ObjectInstance> gone;
    for (const sim::ObjectChange& c : tuesday.plan().changes) {
        if (c.session != 1 || c.what != "removed") continue;
        for (const sim::ObjectInstance& o : tuesday.plan().objects[0])
            if (o.id == c.id) gone = o;
    }
    ASSERT_TRUE(gone) << "tiny_week removes a parked vehicle on Tuesday";
    auto on_it = [&](const map::SiteVersion& v) {
        std::size_t n = 0;
        const Eigen::Rotation2Dd R(-gone->yaw);
        for (const Eigen::Vector3d& p : voxels(v.map_dir(), T_world_map)) {
            const Eigen::Vector2d local = R * (p.head<2>() - Eigen::Vector2d(gone->x, gone->y));
            n += std::abs(local.x()) < 0.5 * gone->size.x() + 0.2 &&
                 std::abs(local.y()) < 0.5 * gone->size.y() + 0.2 && p.z() > gone->base_z + 0.4 &&
                 p.z() < gone->base_z + gone->size.z() + 0.3;
        }
        return n;
    };
    const std::size_t before = on_it(versions[0]), after = on_it(versions[1]);
    EXPECT_GT(before, 3u) << "Monday's map has the vehicle";
    // (2026-11-27: 108 -> 23; what stays was not in view of Tuesday's route, so never judged.)
    EXPECT_LE(after, before / 3) << "Tuesday's version still has " << after << " of its " << before
                                 << " voxels";

    // Wednesday, set down on Tuesday's new ground: localised from its first second of scans, on
    // the truth (Monday's alignment for every day).
    const auto located = tests::poses_by_stamp_ms(path("day2/localisation_tum.txt"));
    const auto truth = tests::poses_by_stamp_ms(path("day2/ground_truth_tum.txt"));
    ASSERT_FALSE(truth.empty());
    const long long start = truth.begin()->first;
    std::size_t early = 0, right = 0, checked = 0;
    for (const auto& [t, T] : located) {
        const auto it = truth.find(t);
        if (it == truth.end()) continue;
        early += t - start <= 1000;
        const double e = ((T_world_map * T).translation() - it->second.translation()).norm();
        ++checked;
        right += e <= 0.5;
    }
    EXPECT_GE(early, 1u) << "no map pose within 1 s of Wednesday's start";
    EXPECT_GE(checked, truth.size() * 9 / 10);
    EXPECT_GE(right, checked * 9 / 10) << right << " of " << checked << " within 0.5 m";
}

}  // namespace
