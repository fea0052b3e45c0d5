// The localisation component through the host: a map saved by a first session of the tiny
// simulated site (built once for the suite, by the composed pipeline with the mapping component),
// then the second session (a kidnapped start, another kidnap on the way) localised on it. A probe
// component of the test host writes what the localisation component publishes to a file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/core/trajectory_io.hpp"
#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "map/core/map_store.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::kTestHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kScenario = ltm::tests::scenario("tiny_loop.yaml");

std::string header(int domain) {
    // A global localisation holds the scans back: the sensor's write waits in one piece.
    return ltm::tests::launch_header(domain, "/robot", "points: stream, ground_truth: stream",
                                     "stream: {max_blocking_s: 2.0}");
}

// What the probe wrote.
struct StatusLine {
    double stamp = 0.0;
    int state = 0;
    bool pose_valid = false, global_ran = false;
    double confidence = 0.0;
    unsigned relocalisations = 0, skipped = 0;
    std::string message;
};
struct Probe {
    std::vector<StatusLine> status;
    std::map<double, Eigen::Isometry3d> poses;  // by stamp, map frame
    std::vector<std::string> events;            // "component level code message"
};

Probe read_probe(const fs::path& file) {
    Probe p;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        std::istringstream ss(line);
        std::string kind;
        ss >> kind;
        if (kind == "status") {
            StatusLine s;
            int valid = 0, global = 0;
            ss >> s.stamp >> s.state >> valid >> global >> s.confidence >> s.relocalisations >>
                s.skipped;
            s.pose_valid = valid;
            s.global_ran = global;
            std::getline(ss >> std::ws, s.message);
            p.status.push_back(s);
        } else if (kind == "pose") {
            double stamp, x, y, z, qx, qy, qz, qw;
            ss >> stamp >> x >> y >> z >> qx >> qy >> qz >> qw;
            Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
            T.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
            T.translation() = Eigen::Vector3d(x, y, z);
            p.poses[stamp] = T;
        } else if (kind == "event") {
            std::string rest;
            std::getline(ss >> std::ws, rest);
            p.events.push_back(rest);
        }
    }
    return p;
}

double yaw(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

class LocalisationPipeline : public ltm::tests::TempDirTest {
  protected:
    LocalisationPipeline() : TempDirTest("ltm_localisation_") {}

    // Session 0 of the tiny site through odometry and mapping: the map and the true poses (once,
    // for the tests that need them).
    static void build_map() {
        if (map_status_ != -1) return;
        suite_dir_ =
            fs::temp_directory_path() / ("ltm_localisation_map_" + std::to_string(getpid()));
        fs::remove_all(suite_dir_);
        fs::create_directories(suite_dir_);
        const std::string cfg = (suite_dir_ / "map.yaml").string();
        std::ofstream(cfg) << header(201) << R"(  - name: sensor
    type: simulator
    params: {scenario: )" << kScenario
                           << R"(, mode: fast, session: 0}
  - name: odometry
    type: odometry
    params: {preset: vlp16}
  - name: mapping
    type: mapping
    params: {preset: vlp16, map_dir: )"
                           << (suite_dir_ / "map").string() << R"(}
  - name: truth
    type: trajectory_writer
    params: {tum_file: )" << (suite_dir_ / "truth0.txt").string()
                           << R"(, input: pose}
    remap: {pose: ground_truth}
)";
        Process host({kHost, cfg}, (suite_dir_ / "map_host").string());
        map_status_ = host.wait(300);
        map_log_ = host.err();
    }
    static void TearDownTestSuite() {
        if (!suite_dir_.empty()) fs::remove_all(suite_dir_);
    }

    // The map's directory; fails the test when it could not be built.
    static std::string map_dir() {
        build_map();
        EXPECT_EQ(map_status_, 0) << map_log_;
        EXPECT_TRUE(fs::exists(suite_dir_ / "map" / "manifest.txt")) << map_log_;
        return (suite_dir_ / "map").string();
    }

    // Session 1 of the site (its first `count` scans, 0: all) localised on `map` through the test
    // host; `probe` adds probe parameters. Offline (skip_while_busy: false) unless `live` (then the
    // map is loaded on the worker while the host runs: `map_load: worker`, not the default).
    std::string localise(int domain, const std::string& map, const std::string& probe = "",
                         int count = 0, bool live = false) {
        return write(
            "localise.yaml", header(domain) + R"(  - name: sensor
    type: simulator
    params: {scenario: )" + kScenario +
                                 R"(, mode: fast, session: 1, wait_for_readers: 2, count: )" +
                                 std::to_string(count) + R"(}
  - name: odometry
    type: odometry
    params: {)" + odometry_params_ +
                                 R"(}
  - name: localisation
    type: localisation
    params: {map: )" + map + R"(, preset: vlp16, skip_while_busy: )" +
                                 (live ? "true, map_load: worker" : "false") + R"(}
  - name: probe
    type: test_localisation_probe
    params: {file: )" + path("probe.txt") +
                                 probe +
                                 R"(}
  - name: truth
    type: trajectory_writer
    params: {tum_file: )" + path("truth1.txt") +
                                 R"(, input: pose}
    remap: {pose: ground_truth}
)");
    }

    std::string odometry_params_ = "preset: vlp16";  // the odometry component's, in localise()

    static fs::path suite_dir_;
    static int map_status_;
    static std::string map_log_;
};

fs::path LocalisationPipeline::suite_dir_;
int LocalisationPipeline::map_status_ = -1;
std::string LocalisationPipeline::map_log_;

}  // namespace

// The start is not told, the robot is lifted and set down elsewhere on the way: every scan gets a
// status, the pose is found at the start and again after the kidnap, every pose that global
// localisation gave is where the simulator's truth says, and so are nearly all the others.
TEST_F(LocalisationPipeline, SecondSessionIsLocalisedOnTheSavedMap) {
    const std::string map = map_dir();
    ASSERT_FALSE(HasFailure());
    Process host({kTestHost, localise(202, map)}, path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();
    const Probe probe = read_probe(dir_ / "probe.txt");
    const common::Trajectory truth1 = common::read_tum_trajectory(path("truth1.txt"));
    const common::Trajectory truth0 =
        common::read_tum_trajectory((suite_dir_ / "truth0.txt").string());
    ASSERT_FALSE(truth0.empty());
    ASSERT_GT(truth1.size(), 20u);
    EXPECT_EQ(probe.status.size(), truth1.size()) << "a status for every scan";
    // The map's frame, from its first keyframe whose scan has a true pose (the frame is the
    // graph's: on a loaded machine the mapper may have joined a local map late).
    const map::LoadedMap loaded = map::load_map(map);
    std::map<std::uint64_t, Eigen::Isometry3d> anchors;
    for (const map::PoseGraphNode& n : loaded.map.nodes) anchors[n.id] = n.T_world_anchor;
    Eigen::Isometry3d T_world_map = Eigen::Isometry3d::Identity();
    bool framed = false;
    for (const auto& k : loaded.map.keyframes) {
        const auto a = anchors.find(k->node);
        if (a == anchors.end()) continue;
        for (const auto& t : truth0) {
            if (std::abs(t.stamp - k->data.stamp) < 1e-4) {
                T_world_map = t.pose * (a->second * k->data.T_anchor_lidar).inverse();
                framed = true;
                break;
            }
        }
        if (framed) break;
    }
    ASSERT_TRUE(framed) << "no keyframe of the map has a true pose";
    std::size_t fixes = 0, near = 0;
    std::string far;  // the scans that are not near, for the failure message
    for (const StatusLine& s : probe.status) {
        const auto truth = std::find_if(truth1.begin(), truth1.end(), [&](const auto& t) {
            return std::abs(t.stamp - s.stamp) < 1e-4;
        });
        ASSERT_NE(truth, truth1.end()) << s.stamp;
        const auto pose = probe.poses.find(s.stamp);
        EXPECT_EQ(pose != probe.poses.end(), s.pose_valid) << s.stamp << ": " << s.message;
        if (pose == probe.poses.end()) continue;
        // Horizontal position and heading: the map's frame, the first scan of session 0, leans
        // as that scan did and the odometry's estimate of it (~2 deg here: ~0.3 m of height
        // 10 m away), which is the map's business, not the localisation's.
        const Eigen::Isometry3d est = T_world_map * pose->second;
        const double dt = (est.translation() - truth->pose.translation()).head<2>().norm();
        const double dr =
            std::abs(std::remainder(yaw(est) - yaw(truth->pose), 2 * M_PI)) * 180.0 / M_PI;
        if (s.state == 3 && s.global_ran) {  // RELOCALISED: no confident wrong pose
            ++fixes;
            EXPECT_LT(dt, 0.3) << s.stamp << ": " << s.message;
            EXPECT_LT(dr, 2.0) << s.stamp << ": " << s.message;
        }
        near += dt < 0.3 && dr < 2.0;
        if (!(dt < 0.3 && dr < 2.0)) {
            std::ostringstream o;
            o << "  " << s.stamp << " state " << s.state << ": " << dt << " m, " << dr
              << " deg: " << s.message << "\n";
            far += o.str();
        }
    }
    EXPECT_GE(fixes, 2u) << "the unknown start and the kidnap";
    EXPECT_GE(10 * near, 9 * probe.status.size()) << far << host.err();  // ~5 cm and 0.1 deg
    EXPECT_EQ(probe.status.back().relocalisations, fixes);
    EXPECT_EQ(probe.status.back().skipped, 0u);  // skip_while_busy: false
    // Relocalisations were said on `status` and in the log.
    std::size_t said = 0;
    for (const std::string& e : probe.events)
        said += e.rfind("localisation 0 relocalised ", 0) == 0;
    EXPECT_EQ(said, fixes);
}

// A map that is not there does not stop the robot: one line in the log, the reason on `status`
// and in every scan's status, no pose, and the host runs to the end. Live with `map_load:
// worker`: the map is loaded on the component's worker once it runs.
TEST_F(LocalisationPipeline, MissingMapIsOneLineAndTheHostRunsOn) {
    const std::string missing = path("no_such_map");
    Process host({kTestHost, localise(203, missing, "", 5, true)}, path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();
    EXPECT_EQ(count(host.err(), "no map to localise on: "), 1u) << host.err();
    EXPECT_NE(host.err().find(missing), std::string::npos) << host.err();
    const Probe probe = read_probe(dir_ / "probe.txt");
    ASSERT_FALSE(probe.status.empty());
    for (const StatusLine& s : probe.status) {
        EXPECT_EQ(s.state, 0);
        EXPECT_FALSE(s.pose_valid);
        EXPECT_EQ(s.message.rfind("no map to localise on: ", 0), 0u) << s.message;
    }
    EXPECT_TRUE(probe.poses.empty());
    ASSERT_FALSE(probe.events.empty());
    EXPECT_EQ(probe.events.front().rfind("localisation 2 no_map no map to localise on: ", 0), 0u)
        << probe.events.front();
}

// A damaged map: the same, with the loader's reason. Offline: the map is loaded before the host
// runs.
TEST_F(LocalisationPipeline, DamagedMapIsOneLineAndTheHostRunsOn) {
    fs::create_directories(dir_ / "broken");
    std::ofstream((dir_ / "broken" / "manifest.txt").string()) << "not a manifest\n";
    Process host({kTestHost, localise(204, path("broken"), "", 5)}, path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();
    EXPECT_EQ(count(host.err(), "no map to localise on: "), 1u) << host.err();
    EXPECT_NE(host.err().find("manifest.txt"), std::string::npos) << host.err();
    EXPECT_TRUE(read_probe(dir_ / "probe.txt").poses.empty());
}

// An operator's initial pose (RViz "2D Pose Estimate") is accepted and forces a global
// localisation on the next scan; one in another frame than the map's is refused with one line. The
// first 10 scans: before the kidnap, where the robot tracks from the start.
TEST_F(LocalisationPipeline, InitialPoseIsAcceptedAndOneInAnotherFrameRefused) {
    const auto globals = [](const Probe& probe) {
        std::size_t n = 0;
        for (const StatusLine& s : probe.status) n += s.global_ran;
        return n;
    };
    const std::string map = map_dir();
    ASSERT_FALSE(HasFailure());
    Process refused({kTestHost, localise(205, map,
                                         ", initial_pose: [10, 4, 90, 0.1], "
                                         "initial_pose_frame: odom",
                                         10)},
                    path("refused"));
    ASSERT_EQ(refused.wait(300), 0) << refused.err();
    EXPECT_EQ(count(refused.err(), "initial pose in frame 'odom' ignored: it must be in 'map'"), 1u)
        << refused.err();
    const Probe without = read_probe(dir_ / "probe.txt");
    EXPECT_EQ(globals(without), 1u) << refused.err();  // the start only

    Process host({kTestHost, localise(206, map, ", initial_pose: [10, 4, 90, 25]", 10)},
                 path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();
    const Probe with = read_probe(dir_ / "probe.txt");
    std::size_t accepted = 0;
    for (const std::string& e : with.events)
        accepted += e.rfind(
                        "localisation 0 initialpose initial pose accepted: (10.00, 4.00) m, "
                        "yaw 90.0 deg; global localisation searches within 15.0 m of it",
                        0) == 0;
    EXPECT_EQ(accepted, 1u) << host.err();
    EXPECT_EQ(with.status.size(), without.status.size());
    EXPECT_EQ(globals(with), 2u) << host.err();  // the start, and the scan after the hint
}

// The localisation preprocesses scans as the odometry component of its host does: an
// odometry.voxel_size override reaches it (not the preset's voxel size), and the log says so.
TEST_F(LocalisationPipeline, OdometryVoxelSizeOverrideReachesTheLocalisation) {
    const std::string map = map_dir();
    ASSERT_FALSE(HasFailure());
    odometry_params_ = "preset: vlp16, voxel_size: 0.45";
    Process host({kTestHost, localise(207, map, "", 5)}, path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();
    EXPECT_NE(host.err().find("scans preprocessed as by the odometry component 'odometry': "
                              "voxel_size 0.45 m"),
              std::string::npos)
        << host.err();
}

// Live with the map loaded at the start (`map_load: start`, the default, as in
// robot_lifelong.yaml): the global queries are asked of their own thread (`localisation/global`),
// not run on the tracking worker. The first scan asks and is not relocalised by itself; every
// relocalisation is the answer of a query for an earlier scan. (The map was loaded before the
// global thread existed, and every query ran on the worker in one piece: issue 28.)
TEST_F(LocalisationPipeline, LiveQueriesRunOnTheirThreadWithTheMapLoadedAtTheStart) {
    const std::string map = map_dir();
    ASSERT_FALSE(HasFailure());
    std::string launch = localise(208, map, "", 30, true);
    {
        std::ifstream in(launch);
        std::stringstream text;
        text << in.rdbuf();
        std::string yaml = text.str();
        const std::size_t at = yaml.find("map_load: worker");
        ASSERT_NE(at, std::string::npos);
        yaml.replace(at, std::string("map_load: worker").size(), "map_load: start");
        std::ofstream(launch) << yaml;
    }
    Process host({kTestHost, launch}, path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();
    const Probe probe = read_probe(dir_ / "probe.txt");
    ASSERT_FALSE(probe.status.empty());
    EXPECT_FALSE(probe.status.front().global_ran) << probe.status.front().message;
    EXPECT_NE(probe.status.front().state, 3) << probe.status.front().message;
    for (const StatusLine& s : probe.status) {
        if (s.state == 3) {
            EXPECT_NE(s.message.find("(the scan at "), std::string::npos) << s.message;
        }
    }
}
