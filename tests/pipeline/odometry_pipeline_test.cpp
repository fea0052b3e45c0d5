// The odometry component through the host on the real KITTI fixture, and on the simulated world.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/core/kitti_io.hpp"
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

const std::string kFixture = std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini";

class OdometryPipeline : public ltm::tests::TempDirTest {
  protected:
    OdometryPipeline() : TempDirTest("ltm_odometry_pipeline_") {}
};

}  // namespace

TEST_F(OdometryPipeline, RealKittiFixtureThroughTheHost) {
    const std::string cfg = write("kitti.yaml", R"(domain_id: 191
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
topics: {points: stream}
components:
  - name: player
    type: kitti_player
    params: {path: )" + kFixture + R"(, mode: fast}
  - name: odometry
    type: odometry
    params: {preset: hdl64, min_scan_points: 50}
  - name: traj
    type: trajectory_writer
    params: {kitti_file: )" + (dir_ / "odometry.txt").string() +
                                                    R"(}
  - name: maps
    type: cloud_writer
    params: {dir: )" + (dir_ / "maps").string() + R"(, inputs: [local_map]}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    ASSERT_EQ(host.wait(120), 0) << host.err();
    EXPECT_NE(host.err().find("3 scans, 3 tracked"), std::string::npos) << host.err();
    const common::PoseList est = common::read_kitti_poses((dir_ / "odometry.txt").string());
    ASSERT_EQ(est.size(), 3u);
    // Against SemanticKITTI's poses in the LiDAR frame (both start at the first scan).
    const common::PoseList ref = common::camera_to_lidar_poses(
        common::read_kitti_poses(kFixture + "/poses_semantickitti.txt"),
        common::read_kitti_calib_tr(kFixture + "/calib.txt"));
    for (std::size_t i = 0; i < 3; ++i) {
        const Eigen::Isometry3d rel_est = est[0].inverse() * est[i];
        const Eigen::Isometry3d rel_ref = ref[0].inverse() * ref[i];
        EXPECT_LT((rel_est.translation() - rel_ref.translation()).norm(), 0.05) << "scan " << i;
    }
    // The local map was handed on at shutdown and written.
    EXPECT_TRUE(fs::exists(dir_ / "maps" / "local_map_0.ply") ||
                fs::exists(dir_ / "maps" / "local_map_1.ply"));
}

// The odometry's default preset (auto): the VLP-16 of tiny_loop told from the first scan, said in
// one line, every scan tracked.
TEST_F(OdometryPipeline, SimulatedWorldThroughTheHost) {
    const std::string scenario = ltm::tests::scenario("tiny_loop.yaml");
    const std::string cfg = write("sim.yaml", R"(domain_id: 192
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
topics: {points: stream, ground_truth: stream}
components:
  - name: sensor
    type: simulator
    params: {scenario: )" + scenario + R"(, mode: fast}
  - name: odometry
    type: odometry
  - name: traj
    type: trajectory_writer
    params: {kitti_file: )" + (dir_ / "odometry.txt").string() +
                                                  R"(}
  - name: truth
    type: trajectory_writer
    params: {kitti_file: )" + (dir_ / "truth.txt").string() +
                                                  R"(, input: pose}
    remap: {pose: ground_truth}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    ASSERT_EQ(host.wait(300), 0) << host.err();
    const common::PoseList est = common::read_kitti_poses((dir_ / "odometry.txt").string());
    const common::PoseList truth = common::read_kitti_poses((dir_ / "truth.txt").string());
    ASSERT_GT(est.size(), 30u);
    ASSERT_EQ(truth.size(), est.size()) << "every scan tracked";
    EXPECT_NE(host.err().find("sensor preset vlp16 (Velodyne VLP-16)"), std::string::npos)
        << host.err();
    // Relative to the first scan, the end of the loop is where the truth says (loose: a test,
    // not a benchmark; ./ltm bench odometry measures accuracy).
    const Eigen::Isometry3d rel_est = est.front().inverse() * est.back();
    const Eigen::Isometry3d rel_truth = truth.front().inverse() * truth.back();
    EXPECT_LT((rel_est.translation() - rel_truth.translation()).norm(), 1.0);
}

// The SLAM back end in the composed pipeline: map saved at shutdown and on request (the request
// sent by the map_request component while the mission runs), corrected full-rate odometry, and a
// second session continuing the saved map.
TEST_F(OdometryPipeline, SlamBackEndSavesItsMapAndASecondSessionContinuesIt) {
    const std::string scenario = ltm::tests::scenario("tiny_loop.yaml");
    auto config = [&](int session, const std::string& extra_mapping, const std::string& tag) {
        return write("slam" + tag + ".yaml",
                     R"(domain_id: 193
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
namespace: /robot
topics: {points: stream}
components:
  - name: sensor
    type: simulator
    params: {scenario: )" +
                         scenario + ", mode: fast, session: " + std::to_string(session) + R"(}
  - name: odometry
    type: odometry
    params: {preset: vlp16}
  - name: mapping
    type: mapping
    params: {preset: vlp16, map_dir: )" +
                         (dir_ / ("map" + tag)).string() + ", global_map_file: " +
                         (dir_ / ("global_map" + tag + ".ply")).string() + extra_mapping + R"(}
  - name: request
    type: map_request
    params: {command: all, map_dir: )" +
                         (dir_ / ("requested" + tag)).string() + ", global_map_file: " +
                         (dir_ / ("requested" + tag + ".ply")).string() + R"(}
  - name: slam
    type: trajectory_writer
    params: {tum_file: )" +
                         (dir_ / ("slam" + tag + ".txt")).string() + R"(, input: path}
  - name: odom
    type: trajectory_writer
    params: {tum_file: )" +
                         (dir_ / ("odometry" + tag + ".txt")).string() + R"(}
  - name: corrected
    type: trajectory_writer
    params: {tum_file: )" +
                         (dir_ / ("corrected" + tag + ".txt")).string() + R"(}
    remap: {odometry: corrected_odometry}
)");
    };
    Process first({kHost, config(0, "", "1")}, (dir_ / "host1").string());
    ASSERT_EQ(first.wait(300), 0) << first.err();
    EXPECT_TRUE(fs::exists(dir_ / "map1" / "manifest.txt")) << first.err();
    EXPECT_TRUE(fs::exists(dir_ / "global_map1.ply"));
    // The request was answered while the mission ran: its map and PLY are where it asked.
    EXPECT_NE(first.err().find("request "), std::string::npos) << first.err();
    EXPECT_TRUE(fs::exists(dir_ / "requested1" / "manifest.txt")) << first.err();
    EXPECT_TRUE(fs::exists(dir_ / "requested1.ply")) << first.err();
    const common::Trajectory path = common::read_tum_trajectory((dir_ / "slam1.txt").string());
    EXPECT_GT(path.size(), 10u);  // the keyframes, at their graph poses
    // Every odometry pose comes out corrected, at the same stamp; in this small map the correction
    // is small (accuracy: ./ltm demo and ./ltm bench slam).
    const common::Trajectory odom = common::read_tum_trajectory((dir_ / "odometry1.txt").string());
    const common::Trajectory corrected =
        common::read_tum_trajectory((dir_ / "corrected1.txt").string());
    ASSERT_GT(odom.size(), 30u);
    ASSERT_EQ(corrected.size(), odom.size());
    for (std::size_t i = 0; i < odom.size(); ++i) {
        EXPECT_DOUBLE_EQ(corrected[i].stamp, odom[i].stamp);
        EXPECT_LT((corrected[i].pose.translation() - odom[i].pose.translation()).norm(), 0.5) << i;
    }
    const auto files = [](const fs::path& dir) {
        std::size_t n = 0;
        for (const auto& e : fs::recursive_directory_iterator(dir))
            n += e.is_regular_file() ? 1 : 0;
        return n;
    };
    const std::size_t first_files = files(dir_ / "map1");

    // Thursday: the map of Monday continued (kept fixed), saved with both sessions in it.
    Process second({kHost, config(1, ", load_map_dir: " + (dir_ / "map1").string(), "2")},
                   (dir_ / "host2").string());
    ASSERT_EQ(second.wait(300), 0) << second.err();
    EXPECT_NE(second.err().find("continuing the map of"), std::string::npos) << second.err();
    EXPECT_GT(files(dir_ / "map2"), first_files);
    EXPECT_EQ(files(dir_ / "map1"), first_files);  // the loaded map is not written to
    // The path is this session's keyframes; every odometry pose comes out corrected.
    const common::Trajectory path2 = common::read_tum_trajectory((dir_ / "slam2.txt").string());
    ASSERT_FALSE(path2.empty());
    EXPECT_GT(path2.front().stamp, path.back().stamp);  // Thursday's, not Monday's
    EXPECT_EQ(common::read_tum_trajectory((dir_ / "corrected2.txt").string()).size(),
              common::read_tum_trajectory((dir_ / "odometry2.txt").string()).size());
}

TEST_F(OdometryPipeline, MapRequestWithoutAMappingComponentFailsWithOneLine) {
    const std::string cfg = write("request.yaml", R"(domain_id: 194
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
namespace: /robot
components:
  - name: request
    type: map_request
    params: {command: save, timeout_s: 1}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    EXPECT_EQ(host.wait(60), 1) << host.err();
    EXPECT_NE(host.err().find("no mapping component listens on '/robot/map_request'"),
              std::string::npos)
        << host.err();
}

TEST_F(OdometryPipeline, MapRequestWithNowhereToWriteIsRefusedWithOneLine) {
    const std::string cfg = write("nowhere.yaml", R"(domain_id: 197
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
components:
  - name: mapping
    type: mapping
  - name: request
    type: map_request
    params: {command: all, global_map_file: )" + (dir_ / "wanted.ply").string() +
                                                      R"(}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    EXPECT_EQ(host.wait(60), 1) << host.err();
    EXPECT_NE(host.err().find(
                  "nowhere to write: no map_dir in the request or the component's parameters"),
              std::string::npos)
        << host.err();
    EXPECT_FALSE(fs::exists(dir_ / "wanted.ply"));  // all or nothing when a target is missing
}

TEST_F(OdometryPipeline, DamagedMapToContinueIsRefusedBeforeAnythingRuns) {
    fs::create_directories(dir_ / "broken");
    std::ofstream((dir_ / "broken" / "manifest.txt").string()) << "not a manifest\n";
    const std::string cfg = write("damaged.yaml", R"(domain_id: 195
components:
  - name: mapping
    type: mapping
    params: {load_map_dir: )" + (dir_ / "broken").string() +
                                                      R"(}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    EXPECT_EQ(host.wait(60), 2) << host.err();
    EXPECT_NE(host.err().find("mapping.load_map_dir: "), std::string::npos) << host.err();
    EXPECT_NE(host.err().find("manifest.txt"), std::string::npos) << host.err();
}

TEST_F(OdometryPipeline, MapOfOtherDescriptorsIsRefusedAtTheScanContextKey) {
    map::MapData map;  // saved with 24 rings; the component keeps the default 20
    map.descriptor_config.rings = 24;
    map::save_map((dir_ / "rings24").string(), map);
    const std::string cfg = write("rings.yaml", R"(domain_id: 196
components:
  - name: mapping
    type: mapping
    params:
      load_map_dir: )" + (dir_ / "rings24").string() +
                                                    R"(
      scan_context: {sectors: 60}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    EXPECT_EQ(host.wait(60), 2) << host.err();
    // The key's own line (the scan_context map), not load_map_dir's.
    EXPECT_NE(host.err().find("rings.yaml:7: mapping.scan_context: differs from the loaded map's "
                              "descriptors (24 x 60"),
              std::string::npos)
        << host.err();
}
