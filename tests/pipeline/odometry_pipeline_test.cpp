// The odometry component through the host on the real KITTI fixture, and on the simulated world.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/core/kitti_io.hpp"
#include "common/core/trajectory_io.hpp"
#include "host/process.hpp"

namespace fs = std::filesystem;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kHost = std::string(LTM_BINARY_DIR) + "/bin/ltm_host";
const std::string kFixture = std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini";

class OdometryPipeline : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("ltm_odometry_pipeline_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir_);
    }
    std::string write(const std::string& name, const std::string& text) {
        std::ofstream((dir_ / name).string()) << text;
        return (dir_ / name).string();
    }
    fs::path dir_;
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
    params: {kitti_file: )" + (dir_ / "odometry.txt").string() + R"(}
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
        common::read_kitti_poses(kFixture + "/poses_semantickitti.txt"), common::read_kitti_calib_tr(kFixture + "/calib.txt"));
    for (std::size_t i = 0; i < 3; ++i) {
        const Eigen::Isometry3d rel_est = est[0].inverse() * est[i];
        const Eigen::Isometry3d rel_ref = ref[0].inverse() * ref[i];
        EXPECT_LT((rel_est.translation() - rel_ref.translation()).norm(), 0.05) << "scan " << i;
    }
    // The local map was handed on at shutdown and written.
    EXPECT_TRUE(fs::exists(dir_ / "maps" / "local_map_0.ply") || fs::exists(dir_ / "maps" / "local_map_1.ply"));
}

TEST_F(OdometryPipeline, SimulatedWorldThroughTheHost) {
    const std::string scenario = std::string(LTM_SOURCE_DIR) + "/components/simulator/scenarios/tiny_loop.yaml";
    const std::string cfg = write("sim.yaml", R"(domain_id: 192
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
topics: {points: stream, ground_truth: stream}
components:
  - name: sensor
    type: simulator
    params: {scenario: )" + scenario + R"(, mode: fast}
  - name: odometry
    type: odometry
    params: {preset: vlp16}
  - name: traj
    type: trajectory_writer
    params: {kitti_file: )" + (dir_ / "odometry.txt").string() + R"(}
  - name: truth
    type: trajectory_writer
    params: {kitti_file: )" + (dir_ / "truth.txt").string() + R"(, input: pose}
    remap: {pose: ground_truth}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    ASSERT_EQ(host.wait(300), 0) << host.err();
    const common::PoseList est = common::read_kitti_poses((dir_ / "odometry.txt").string());
    const common::PoseList truth = common::read_kitti_poses((dir_ / "truth.txt").string());
    ASSERT_GT(est.size(), 30u);
    ASSERT_EQ(truth.size(), est.size()) << "every scan tracked";
    // Relative to the first scan, the end of the loop is where the truth says (loose: a test,
    // not a benchmark; ./ltm bench odometry measures accuracy).
    const Eigen::Isometry3d rel_est = est.front().inverse() * est.back();
    const Eigen::Isometry3d rel_truth = truth.front().inverse() * truth.back();
    EXPECT_LT((rel_est.translation() - rel_truth.translation()).norm(), 1.0);
}

TEST_F(OdometryPipeline, SlamBackEndSavesItsMapAndPath) {
    const std::string scenario = std::string(LTM_SOURCE_DIR) + "/components/simulator/scenarios/tiny_loop.yaml";
    const std::string cfg = write("slam.yaml", R"(domain_id: 193
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
topics: {points: stream}
components:
  - name: sensor
    type: simulator
    params: {scenario: )" + scenario + R"(, mode: fast}
  - name: odometry
    type: odometry
    params: {preset: vlp16}
  - name: mapping
    type: mapping
    params: {map_dir: )" + (dir_ / "map").string() + ", global_map_file: " + (dir_ / "global_map.ply").string() + R"(}
  - name: slam
    type: trajectory_writer
    params: {tum_file: )" + (dir_ / "slam_tum.txt").string() + R"(, input: path}
)");
    Process host({kHost, cfg}, (dir_ / "host").string());
    ASSERT_EQ(host.wait(300), 0) << host.err();
    EXPECT_TRUE(fs::exists(dir_ / "map" / "manifest.txt")) << host.err();
    EXPECT_TRUE(fs::exists(dir_ / "global_map.ply"));
    const common::Trajectory path = common::read_tum_trajectory((dir_ / "slam_tum.txt").string());
    EXPECT_GT(path.size(), 10u);  // the keyframes, at their graph poses
}
