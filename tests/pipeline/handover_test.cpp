// The live pipeline (player -> odometry -> mapping, through the host and DDS) and the offline one
// (slam::SlamPipeline on the same scans) hand the mapper the same local maps, with the same
// observation times, and the same keyframes: one hand-over policy on both sides.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "map/core/map_store.hpp"
#include "slam/core/slam_pipeline.hpp"
#include "sources/core/scan_folder.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kFixture = std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini";

class Handover : public ltm::tests::TempDirTest {
  protected:
    Handover() : TempDirTest("ltm_handover_") {}
};

// Stamps travel as builtin_interfaces/Time (integer nanoseconds) on the live side.
bool same_stamp(double a, double b) { return std::abs(a - b) <= 1e-9; }
bool same_stamps(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (!same_stamp(a[i], b[i])) return false;
    }
    return true;
}

void expect_same_map(const common::LocalMapData& live, const common::LocalMapData& offline) {
    const std::string id = "local map " + std::to_string(live.id);
    EXPECT_EQ(live.finished, offline.finished) << id;
    EXPECT_EQ(live.segment, offline.segment) << id;
    EXPECT_TRUE(same_stamps(live.observation_times, offline.observation_times)) << id;
    EXPECT_TRUE(live.T_odom_anchor.isApprox(offline.T_odom_anchor, 1e-12)) << id;
    EXPECT_TRUE(live.T_anchor_grid.isApprox(offline.T_anchor_grid, 1e-12)) << id;
    ASSERT_EQ(live.voxels.size(), offline.voxels.size()) << id;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < live.voxels.size(); ++i) {
        const common::VoxelData &a = live.voxels[i], &b = offline.voxels[i];
        differ += a.index != b.index || a.centre != b.centre || a.normal != b.normal ||
                  a.point_count != b.point_count || a.life.observations != b.life.observations ||
                  !same_stamp(a.life.created, b.life.created) ||
                  !same_stamp(a.life.last_seen, b.life.last_seen);
    }
    EXPECT_EQ(differ, 0u) << id << ": voxels that differ";
}

}  // namespace

TEST_F(Handover, LiveAndOfflinePipelinesHandOverTheSameMapsAndKeyframes) {
    // Live: every scan delivered (points as a reliable stream), one worker thread (deterministic),
    // a snapshot at every keyframe; the mapping component saves its map at shutdown.
    const std::string cfg = write("live.yaml", R"(domain_id: 193
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
topics: {points: stream}
components:
  - name: player
    type: kitti_player
    params: {path: )" + kFixture + R"(, mode: fast}
  - name: odometry
    type: odometry
    params: {preset: hdl64, min_scan_points: 50, threads: 1, keyframe: {distance: 0.3}, snapshot_every_keyframes: 1}
  - name: mapping
    type: mapping
    params: {preset: hdl64, map_dir: )" + (dir_ / "map").string() +
                                                   R"(, save_period_s: 0}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    ASSERT_EQ(host.wait(120), 0) << host.err();
    const map::LoadedMap live = map::load_map((dir_ / "map").string());
    ASSERT_TRUE(live.refused.empty()) << live.refused.front();

    // Offline: the same scans, the same settings.
    sources::ScanFolderConfig folder;
    folder.path = kFixture;
    folder.format = sources::ScanFormat::kAuto;
    const sources::ScanFolder scans(folder);
    slam::SlamPipelineConfig pc;
    pc.odometry = odometry::preset_config(common::SensorPreset::kHdl64);
    pc.odometry.min_scan_points = 50;
    pc.odometry.threads = 1;
    pc.odometry.keyframe.distance = 0.3;
    pc.mapping = mapping::mapper_preset(common::SensorPreset::kHdl64);
    pc.handover.snapshot_every_keyframes = 1;
    slam::SlamPipeline pipeline(pc);
    std::size_t snapshots = 0;
    for (std::size_t i = 0; i < scans.size(); ++i) {
        const slam::SlamFrame f = pipeline.process(scans.load(i));
        ASSERT_TRUE(f.odometry.pose_valid()) << f.odometry.message;
        for (const common::LocalMapData& m : f.handover.local_maps) snapshots += !m.finished;
    }
    pipeline.finish();
    EXPECT_GE(snapshots, 1u) << "the fixture's keyframes hand over snapshots";
    const map::MapData offline = pipeline.mapper().snapshot();

    ASSERT_EQ(live.map.local_maps.size(), offline.local_maps.size());
    for (std::size_t k = 0; k < offline.local_maps.size(); ++k) {
        const common::LocalMapData& a = *live.map.local_maps[k].data;
        const common::LocalMapData& b = *offline.local_maps[k].data;
        ASSERT_EQ(a.id, b.id);
        EXPECT_TRUE(a.finished) << "the finished map reached the live mapper";
        EXPECT_EQ(a.observation_times.size(), scans.size()) << "every scan updated the map";
        expect_same_map(a, b);
    }
    ASSERT_EQ(live.map.keyframes.size(), offline.keyframes.size()) << host.err();
    ASSERT_GE(offline.keyframes.size(), 2u);
    for (std::size_t k = 0; k < offline.keyframes.size(); ++k) {
        const common::KeyframeData& a = live.map.keyframes[k]->data;
        const common::KeyframeData& b = offline.keyframes[k]->data;
        EXPECT_EQ(a.scan_index, b.scan_index);
        EXPECT_EQ(a.local_map_id, b.local_map_id);
        EXPECT_TRUE(same_stamp(a.stamp, b.stamp));
        EXPECT_TRUE(a.T_anchor_lidar.isApprox(b.T_anchor_lidar, 1e-12));
        EXPECT_EQ(a.points, b.points);
    }
}
