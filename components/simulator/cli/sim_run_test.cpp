#include "simulator/cli/sim_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/cli/cli.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"
#include "common/core/point_labels.hpp"
#include "common/core/trajectory_io.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"
#include "sources/core/scan_folder.hpp"

namespace ltm::sim::cli {
namespace {

const std::string kTiny = LTM_SOURCE_DIR "/components/simulator/scenarios/tiny_loop.yaml";
const std::string kFastTurns = LTM_SOURCE_DIR "/components/simulator/scenarios/fast_turns.yaml";

// Parses a command line as ltm_sim does: the exit code (-1: go on) and what went to stderr.
int parse_sim_args(const std::vector<std::string>& args, SimRunOptions& o, std::string& error) {
    CLI::App app{"ltm_sim", "ltm_sim"};
    add_sim_options(app, o);
    std::ostringstream out, err;
    const int code = common::cli::parse(app, args, out, err);
    error = err.str();
    return code;
}

std::size_t file_size(const std::string& path) { return std::filesystem::file_size(path); }

TEST(SimRun, ParsesOptions) {
    SimRunOptions o;
    std::string error;
    ASSERT_EQ(parse_sim_args({"s.yaml", "--seed", "9", "--session", "1", "--frames",
                              "5:", "--sensor", "vlp16", "--out", "d"},
                             o, error),
              -1)
        << error;
    EXPECT_EQ(o.scenario, "s.yaml");
    EXPECT_TRUE(o.has_seed);
    EXPECT_EQ(o.seed, 9u);
    EXPECT_EQ(o.session, 1);
    EXPECT_EQ(o.first, 5u);
    EXPECT_EQ(o.last, std::numeric_limits<std::size_t>::max());
    EXPECT_EQ(o.sensor, "vlp16");
    EXPECT_EQ(o.out, "d");
    EXPECT_EQ(o.format, "kitti");
    SimRunOptions p;
    ASSERT_EQ(parse_sim_args({"s.yaml", "--format", "pcd", "--out", "d"}, p, error), -1) << error;
    EXPECT_EQ(p.format, "pcd");
    const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
        {{"s.yaml"}, "--out: is required"},
        {{"--out", "d"}, "SCENARIO: is required"},
        {{"s.yaml", "--out", "d", "--frames", "9:3"},
         "--frames: expected A:B with A < B (e.g. 0:100, 50:), got '9:3'"},
        {{"s.yaml", "--out", "d", "--seed", "x"},
         "--seed: expected a non-negative integer, got 'x'"},
        {{"s.yaml", "--out", "d", "--session", "-1"}, "--session: must be at least 0, not -1"},
        {{"s.yaml", "--out", "d", "--fast"}, "--fast: unknown option"},
        {{"s.yaml", "t.yaml", "--out", "d"}, "t.yaml: unexpected argument"},
        {{"s.yaml", "--out"}, "--out: needs a value"},
        {{"s.yaml", "--out", "d", "--format", "las"}, "--format: must be kitti|pcd, not 'las'"}};
    for (const auto& [args, message] : bad) {
        SimRunOptions b;
        EXPECT_EQ(parse_sim_args(args, b, error), 2);
        EXPECT_EQ(error, "ltm_sim: " + message + "\n");
    }
    SimRunOptions h;
    EXPECT_EQ(parse_sim_args({"--help"}, h, error), 0);
}

TEST(SimRun, WritesAKittiFolderThatReadsBack) {
    const std::string out = LTM_BINARY_DIR "/tests/sim_run_test_out";
    std::filesystem::remove_all(out);
    SimRunOptions o;
    std::string error;
    ASSERT_EQ(parse_sim_args({kTiny, "--session", "1", "--frames", "0:4", "--quiet", "--out", out},
                             o, error),
              -1);
    ASSERT_EQ(run_sim(o), 0);
    const auto scans = common::list_kitti_scans(out);
    ASSERT_EQ(scans.size(), 4u);
    for (std::size_t i = 0; i < scans.size(); ++i) {
        const common::PointCloud cloud = common::read_kitti_bin(scans[i]);
        EXPECT_GT(cloud.size(), 3000u);
        char name[64];
        std::snprintf(name, sizeof name, "/labels/%06zu.label", i);
        EXPECT_EQ(file_size(out + name), 4 * cloud.size());
        for (const auto& p : cloud.points) EXPECT_LT(p.norm(), 100.5f);
    }
    EXPECT_EQ(common::read_times(out + "/times.txt").size(), 4u);
    const auto poses = common::read_kitti_poses(out + "/poses.txt");
    ASSERT_EQ(poses.size(), 4u);
    const auto tum = common::read_tum_trajectory(out + "/poses_tum.txt");
    ASSERT_EQ(tum.size(), 4u);
    EXPECT_TRUE(tum[2].pose.isApprox(poses[2], 1e-6));
    EXPECT_TRUE(
        common::read_kitti_calib_tr(out + "/calib.txt").isApprox(Eigen::Isometry3d::Identity()));
    for (const char* f : {"/truth_mesh.ply", "/scenario.yaml", "/objects.txt", "/changes.txt",
                          "/actors.txt", "/kidnaps.txt"}) {
        EXPECT_TRUE(std::filesystem::exists(out + f)) << f;
    }
    EXPECT_GT(file_size(out + "/truth_mesh.ply"), 100000u);
    std::ifstream kid(out + "/kidnaps.txt");
    std::string header, first;
    std::getline(kid, header);
    std::getline(kid, first);
    EXPECT_EQ(first.rfind("0 ", 0), 0u);  // session 1 starts kidnapped
}

// --truth-only: the truth files of every scan, the same poses and kidnaps as rendering gives,
// no scans, labels or mesh.
TEST(SimRun, TruthOnlyWritesTheTruthFilesWithoutScans) {
    const std::string out = LTM_BINARY_DIR "/tests/sim_run_test_truth";
    const std::string full = LTM_BINARY_DIR "/tests/sim_run_test_truth_full";
    std::filesystem::remove_all(out);
    std::filesystem::remove_all(full);
    SimRunOptions o, f;
    std::string error;
    ASSERT_EQ(parse_sim_args({kTiny, "--session", "1", "--truth-only", "--quiet", "--out", out}, o,
                             error),
              -1);
    EXPECT_TRUE(o.truth_only);
    ASSERT_EQ(run_sim(o), 0);
    ASSERT_EQ(parse_sim_args({kTiny, "--session", "1", "--quiet", "--out", full}, f, error), -1);
    ASSERT_EQ(run_sim(f), 0);
    EXPECT_FALSE(std::filesystem::exists(out + "/velodyne"));
    EXPECT_FALSE(std::filesystem::exists(out + "/labels"));
    EXPECT_FALSE(std::filesystem::exists(out + "/truth_mesh.ply"));
    const auto tum = common::read_tum_trajectory(out + "/poses_tum.txt");
    const auto rendered = common::read_tum_trajectory(full + "/poses_tum.txt");
    ASSERT_EQ(tum.size(), rendered.size());
    ASSERT_GT(tum.size(), 20u);
    for (std::size_t i = 0; i < tum.size(); ++i) {
        EXPECT_DOUBLE_EQ(tum[i].stamp, rendered[i].stamp);
        EXPECT_TRUE(tum[i].pose.isApprox(rendered[i].pose, 1e-9)) << i;
    }
    for (const char* name : {"/kidnaps.txt", "/objects.txt", "/changes.txt", "/actors.txt"}) {
        std::ifstream a(out + name), b(full + name);
        std::stringstream ta, tb;
        ta << a.rdbuf();
        tb << b.rdbuf();
        EXPECT_EQ(ta.str(), tb.str()) << name;
    }
}

// Raw sweeps as PCD keep their per-point time through the scan folder reader.
TEST(SimRun, WritesPcdScansWithPerPointTime) {
    const std::string out = LTM_BINARY_DIR "/tests/sim_run_test_pcd";
    std::filesystem::remove_all(out);
    SimRunOptions o;
    std::string error;
    ASSERT_EQ(
        parse_sim_args({kFastTurns, "--frames", "0:3", "--format", "pcd", "--quiet", "--out", out},
                       o, error),
        -1);
    ASSERT_EQ(run_sim(o), 0);
    EXPECT_FALSE(std::filesystem::exists(out + "/velodyne"));
    sources::ScanFolderConfig cfg;
    cfg.path = out;
    cfg.format = sources::ScanFormat::kAuto;
    cfg.poses_file = out + "/poses.txt";
    const sources::ScanFolder folder(cfg);
    ASSERT_EQ(folder.format(), sources::ScanFormat::kCloudFiles);
    ASSERT_EQ(folder.size(), 3u);
    ASSERT_TRUE(folder.has_times());
    ASSERT_TRUE(folder.has_poses());
    const Simulator sim(load_scenario(kFastTurns));
    SimScan scan;
    for (std::size_t i = 0; i < folder.size(); ++i) {
        ASSERT_TRUE(sim.scan(i, scan));
        const common::PointCloud cloud = folder.load(i);
        EXPECT_DOUBLE_EQ(cloud.stamp, scan.cloud.stamp);
        ASSERT_EQ(cloud.size(), scan.cloud.size());
        ASSERT_TRUE(cloud.has_time());
        ASSERT_EQ(cloud.time, scan.cloud.time);
        EXPECT_EQ(cloud.intensity, scan.cloud.intensity);
        EXPECT_EQ(cloud.points[7], scan.cloud.points[7]);
        EXPECT_TRUE(folder.pose(i).isApprox(sim.pose(i), 1e-6));
        const auto [lo, hi] = std::minmax_element(cloud.time.begin(), cloud.time.end());
        EXPECT_GE(*lo, 0.0f);
        EXPECT_LT(*hi, 0.1f);
        EXPECT_GT(*hi - *lo, 0.09f);  // a whole sweep
    }
    // A snapshot scan (no motion distortion) has no times to write.
    SimRunOptions still = o;
    still.scenario = kTiny;
    still.out = out + "_still";
    ASSERT_EQ(run_sim(still), 0);
    const common::PointCloud cloud = common::load_cloud_file(still.out + "/Scans/000000.pcd");
    EXPECT_GT(cloud.size(), 3000u);
    EXPECT_FALSE(cloud.has_time());
    EXPECT_TRUE(cloud.has_intensity());
    std::filesystem::remove_all(out);
    std::filesystem::remove_all(still.out);
}

TEST(SimRun, BadInputIsAnErrorNotACrash) {
    SimRunOptions o;
    o.scenario = "/nonexistent.yaml";
    o.out = LTM_BINARY_DIR "/tests/sim_run_test_none";
    o.quiet = true;
    EXPECT_EQ(run_sim(o), 1);
    o.scenario = kTiny;
    o.session = 5;
    EXPECT_EQ(run_sim(o), 1);
    o.session = 0;
    o.sensor = "lidar9";
    EXPECT_EQ(run_sim(o), 1);
    o.sensor.clear();
    o.first = 100000;
    o.last = 100001;
    EXPECT_EQ(run_sim(o), 2);
}

}  // namespace
}  // namespace ltm::sim::cli

namespace ltm::sim::cli {
namespace {

// Lines of a text file that are not comments.
std::vector<std::string> data_lines(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] != '#') out.push_back(line);
    return out;
}

// The robot's motion sensors beside the scans: IMU and wheel odometry at their rates over the
// scans' time (to the last sweep's end), the extrinsics; --point-stride thins the scans.
TEST(SimRun, WritesTheRobotsMotionSensorsAndThinsScans) {
    const std::string out = LTM_BINARY_DIR "/tests/sim_run_test_motion";
    std::filesystem::remove_all(out);
    SimRunOptions o;
    std::string error;
    ASSERT_EQ(parse_sim_args({kFastTurns, "--frames", "0:3", "--imu-rate", "100", "--wheel-rate",
                              "20", "--point-stride", "4", "--quiet", "--out", out},
                             o, error),
              -1)
        << error;
    ASSERT_EQ(run_sim(o), 0);
    const std::vector<double> times = common::read_times(out + "/times.txt");
    ASSERT_EQ(times.size(), 3u);
    const std::vector<std::string> imu = data_lines(out + "/imu.txt");
    const std::vector<std::string> wheel = data_lines(out + "/wheel_odometry.txt");
    EXPECT_EQ(imu.size(), 30u);  // 0.3 s at 100 Hz
    EXPECT_EQ(wheel.size(), 6u);
    for (std::size_t i = 0; i < imu.size(); ++i) {
        std::istringstream s(imu[i]);
        const std::string& l = imu[i];
        double v[7];
        for (double& x : v) s >> x;
        ASSERT_TRUE(bool(s)) << l;
        EXPECT_GE(v[0], times.front() - 1e-9);
        EXPECT_LT(v[0], times.back() + 0.1);
        // Gravity while driving; the route starts at full speed: the first sample saturates.
        if (i > 0) {
            EXPECT_NEAR(Eigen::Vector3d(v[4], v[5], v[6]).norm(), 9.81, 3.0) << l;
        }
    }
    const std::vector<std::string> extrinsics = data_lines(out + "/extrinsics.txt");
    ASSERT_EQ(extrinsics.size(), 2u);
    EXPECT_EQ(extrinsics[0].rfind("T_lidar_imu ", 0), 0u);
    EXPECT_EQ(extrinsics[1].rfind("T_lidar_base ", 0), 0u);
    // Every 4th point of the full scan.
    const Simulator sim(load_scenario(kFastTurns));
    SimScan full;
    ASSERT_TRUE(sim.scan(1, full));
    const common::PointCloud thin = common::read_kitti_bin(common::list_kitti_scans(out)[1]);
    EXPECT_EQ(thin.size(), (full.cloud.size() + 3) / 4);
    EXPECT_TRUE(thin.points[5].isApprox(full.cloud.points[20], 1e-5f));
    // --imu-rate 0 --wheel-rate 0: none of them.
    const std::string bare = out + "_bare";
    std::filesystem::remove_all(bare);
    SimRunOptions b;
    ASSERT_EQ(parse_sim_args({kFastTurns, "--frames", "0:1", "--imu-rate", "0", "--wheel-rate", "0",
                              "--quiet", "--out", bare},
                             b, error),
              -1);
    ASSERT_EQ(run_sim(b), 0);
    EXPECT_FALSE(std::filesystem::exists(bare + "/imu.txt"));
    EXPECT_FALSE(std::filesystem::exists(bare + "/extrinsics.txt"));
}

}  // namespace
}  // namespace ltm::sim::cli
