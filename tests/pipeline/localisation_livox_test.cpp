// A Livox (the simulator's livox_avia, ~70 deg around) under `preset: auto` through the host: the
// localisation tells the sensor from its first scan and takes the narrow preset's localiser and
// map settings (the map, loaded before that scan, loaded again with them), and localises the second
// session of the tiny site on a map made with `preset: narrow` as well as with `narrow` named.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
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

std::string header(int domain) {
    return ltm::tests::launch_header(domain, "/robot", "points: stream, ground_truth: stream",
                                     "stream: {max_blocking_s: 2.0}");
}

std::string sensor(int session) {
    return "  - name: sensor\n    type: simulator\n    params: {scenario: " + kScenario +
           ", mode: fast, session: " + std::to_string(session) +
           ", sensor: livox_avia, wait_for_readers: 2}\n";
}

std::string writer(const std::string& name, const std::string& file, const std::string& input,
                   const std::string& topic) {
    // Both inputs are on the writer's topic `pose`.
    return "  - name: " + name + "\n    type: trajectory_writer\n    params: {tum_file: " + file +
           ", input: " + input + "}\n    remap: {pose: " + topic + "}\n";
}

class LivoxAutoPipeline : public ltm::tests::TempDirTest {
  protected:
    LivoxAutoPipeline() : TempDirTest("ltm_localisation_livox_") {}

    // Session 1 localised with `preset` (the odometry's and the localisation's): the scans whose
    // published map pose is within 0.3 m and 2 deg of the truth (horizontal), and the host's log.
    std::size_t localise(int domain, const std::string& preset, std::string* log) {
        const std::string cfg = write(
            "localise_" + preset + ".yaml",
            header(domain) + sensor(1) + "  - name: odometry\n    type: odometry\n" +
                "    params: {preset: " + preset + "}\n" +
                "  - name: localisation\n    type: localisation\n    params: {map: " + path("map") +
                ", preset: " + preset + ", skip_while_busy: false}\n" +
                writer("poses", path("pose_" + preset + ".txt"), "pose_with_covariance", "pose") +
                writer("truth", path("truth1.txt"), "pose", "ground_truth"));
        Process host({kHost, cfg}, path("host_" + preset));
        EXPECT_EQ(host.wait(300), 0) << host.err();
        *log = host.err();
        const common::Trajectory poses =
            common::read_tum_trajectory(path("pose_" + preset + ".txt"));
        const common::Trajectory truth = common::read_tum_trajectory(path("truth1.txt"));
        EXPECT_GT(truth.size(), 20u);
        std::size_t near = 0;
        for (const auto& p : poses)
            for (const auto& t : truth) {
                if (std::abs(t.stamp - p.stamp) > 1e-4) continue;
                const Eigen::Isometry3d est = T_world_map_ * p.pose;
                const double dt = (est.translation() - t.pose.translation()).head<2>().norm();
                const Eigen::Matrix3d R = est.linear().transpose() * t.pose.linear();
                const double dr = std::abs(std::atan2(R(1, 0), R(0, 0))) * 180.0 / M_PI;
                near += dt < 0.3 && dr < 2.0;
            }
        std::printf("preset %s: %zu of %zu scans with a map pose within 0.3 m and 2 deg\n",
                    preset.c_str(), near, truth.size());
        return near;
    }

    // Session 0 mapped with the narrow preset named; the map's frame in the world from its first
    // keyframe with a true pose (as in localisation_test).
    void make_map(int domain) {
        const std::string cfg = write(
            "map.yaml", header(domain) + sensor(0) +
                            "  - name: odometry\n    type: odometry\n    params: {preset: narrow}\n"
                            "  - name: mapping\n    type: mapping\n    params: {preset: narrow, "
                            "map_dir: " +
                            path("map") + "}\n" +
                            writer("truth", path("truth0.txt"), "pose", "ground_truth"));
        Process host({kHost, cfg}, path("map_host"));
        ASSERT_EQ(host.wait(300), 0) << host.err();
        const common::Trajectory truth0 = common::read_tum_trajectory(path("truth0.txt"));
        const map::LoadedMap loaded = map::load_map(path("map"));
        std::map<std::uint64_t, Eigen::Isometry3d> anchors;
        for (const map::PoseGraphNode& n : loaded.map.nodes) anchors[n.id] = n.T_world_anchor;
        for (const auto& k : loaded.map.keyframes) {
            const auto a = anchors.find(k->node);
            if (a == anchors.end()) continue;
            for (const auto& t : truth0)
                if (std::abs(t.stamp - k->data.stamp) < 1e-4) {
                    T_world_map_ = t.pose * (a->second * k->data.T_anchor_lidar).inverse();
                    return;
                }
        }
        FAIL() << "no keyframe of the map has a true pose";
    }

    Eigen::Isometry3d T_world_map_ = Eigen::Isometry3d::Identity();
};

}  // namespace

TEST_F(LivoxAutoPipeline, AutoLocalisesAsNarrowNamed) {
    make_map(218);
    ASSERT_FALSE(HasFailure());
    std::string auto_log, narrow_log;
    const std::size_t with_auto = localise(219, "auto", &auto_log);
    const std::size_t with_narrow = localise(219, "narrow", &narrow_log);
    ASSERT_FALSE(HasFailure());
    EXPECT_NE(auto_log.find("[localisation] preset auto: the scans are a narrow sensor's: the "
                            "localiser's and the map's settings of preset narrow"),
              std::string::npos)
        << auto_log;
    // The map loaded at start (spinning settings), then again with the narrow ones.
    std::size_t loads = 0;
    for (std::size_t at = auto_log.find("[localisation] loading the map "); at != std::string::npos;
         at = auto_log.find("[localisation] loading the map ", at + 1))
        ++loads;
    EXPECT_EQ(loads, 2u) << auto_log;
    EXPECT_GE(with_narrow, 30u) << narrow_log;
    // As well as named: at most a scan or two apart (the runs are not bit-identical on a loaded
    // machine: the odometry's timing differs).
    EXPECT_GE(with_auto + 2, with_narrow) << auto_log;
}
