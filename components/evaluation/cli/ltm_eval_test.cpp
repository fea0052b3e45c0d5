// End-to-end checks of the ltm_eval command line on small files with known answers.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/kitti_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/point_labels.hpp"
#include "common/core/trajectory_io.hpp"
#include "evaluation/core/eval_io.hpp"

namespace ltm::eval {
namespace {

namespace fs = std::filesystem;

struct CliRun {
    int code;
    std::string output;
};

CliRun run(const std::string& args) {
    // One file per process: ctest runs this binary's tests in parallel processes.
    const std::string log =
        testing::TempDir() + "ltm_eval_cli_output_" + std::to_string(::getpid()) + ".txt";
    const std::string cmd =
        std::string(LTM_BINARY_DIR) + "/bin/ltm_eval " + args + " > " + log + " 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    return {WEXITSTATUS(status), ss.str()};
}

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

fs::path fresh_dir(const std::string& name) {
    const fs::path d = fs::path(testing::TempDir()) / ("ltm_eval_cli_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// 61 frames along x, 1 m apart; the estimate's steps are 1 % long.
void straight_files(const fs::path& dir) {
    common::PoseList ref, est;
    for (int i = 0; i <= 60; ++i) {
        Eigen::Isometry3d r = Eigen::Isometry3d::Identity(), e = r;
        r.translation().x() = i;
        e.translation().x() = 1.01 * i;
        ref.push_back(r);
        est.push_back(e);
    }
    common::write_kitti_poses((dir / "ref.txt").string(), ref);
    common::write_kitti_poses((dir / "est.txt").string(), est);
}

TEST(LtmEvalCli, TrajWritesMetricsAndFigures) {
    const fs::path d = fresh_dir("traj");
    straight_files(d);
    const CliRun r = run("traj --estimate " + (d / "est.txt").string() + " --reference " +
                         (d / "ref.txt").string() + " --out " + (d / "out").string());
    ASSERT_EQ(r.code, 0) << r.output;
    // Hand-computed in kitti_metric_test: 15 segments, 1.058 %.
    const std::string json = read(d / "out" / "metrics.json");
    EXPECT_NE(json.find("\"translation_pct\": 1.058"), std::string::npos) << json;
    EXPECT_NE(json.find("\"segments\": 15"), std::string::npos) << json;
    EXPECT_NE(r.output.find("kitti_short_10_50m"), std::string::npos);
    for (const char* f : {"metrics.txt", "trajectory.svg", "errors.svg", "estimate_aligned.txt"})
        EXPECT_TRUE(fs::exists(d / "out" / f)) << f;
    EXPECT_EQ(read(d / "out" / "trajectory.svg").rfind("<?xml", 0), 0u);
}

TEST(LtmEvalCli, BadInputGivesOneLineAndAnExitCode) {
    const CliRun unknown = run("traj --bogus 1");
    EXPECT_EQ(unknown.code, 2);
    EXPECT_EQ(unknown.output, "ltm_eval traj: --bogus: unknown option\n");
    const CliRun no_value = run("traj --estimate a --reference b --delta");
    EXPECT_EQ(no_value.code, 2);
    EXPECT_EQ(no_value.output, "ltm_eval traj: --delta: needs a value\n");
    const CliRun not_a_number = run("mesh --mesh a --truth b --threshold 1cm");
    EXPECT_EQ(not_a_number.code, 2);
    EXPECT_EQ(not_a_number.output, "ltm_eval mesh: --threshold: expected a number, got '1cm'\n");
    const CliRun too_small = run("traj --estimate a --reference b --delta 0");
    EXPECT_EQ(too_small.code, 2);
    EXPECT_EQ(too_small.output, "ltm_eval traj: --delta: must be at least 1, not 0\n");
    const CliRun choice = run("traj --estimate a --reference b --format csv");
    EXPECT_EQ(choice.code, 2);
    EXPECT_EQ(choice.output, "ltm_eval traj: --format: must be kitti|tum, not 'csv'\n");
    const CliRun required = run("loops --loops l.txt");
    EXPECT_EQ(required.code, 2);
    EXPECT_EQ(required.output, "ltm_eval loops: --reference: is required\n");
    const CliRun neither = run("dynamic --map m.ply");
    EXPECT_EQ(neither.code, 2);
    EXPECT_EQ(neither.output, "ltm_eval dynamic: give either --scans DIR or --truth FILE\n");
    const CliRun travel = run("dynamic --scans d --min-travel -1");
    EXPECT_EQ(travel.code, 2);
    EXPECT_EQ(travel.output, "ltm_eval dynamic: --min-travel: must be at least 0, not -1\n");
    const CliRun missing = run("traj --estimate /nonexistent/a.txt --reference /nonexistent/b.txt");
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.output.find("/nonexistent/a.txt: cannot open"), std::string::npos);
    EXPECT_EQ(run("nosuchcommand").output,
              "ltm_eval: nosuchcommand: unknown command (traj, dynamic, mesh, loops, reloc, "
              "lifelong, report)\n");
    EXPECT_EQ(
        run("").output,
        "ltm_eval: a command is required (traj, dynamic, mesh, loops, reloc, lifelong, report)\n");
    EXPECT_EQ(run("").code, 2);
    EXPECT_EQ(run("traj --estimate a --reference b --reference-frame camera").code, 1);
}

TEST(LtmEvalCli, HelpListsTheCommandsAndTheirOptions) {
    const CliRun top = run("--help");
    EXPECT_EQ(top.code, 0);
    for (const char* c : {"traj", "dynamic", "mesh", "loops", "reloc", "lifelong"})
        EXPECT_NE(top.output.find(c), std::string::npos) << c;
    const CliRun traj = run("traj --help");
    EXPECT_EQ(traj.code, 0);
    for (const char* o : {"--estimate", "--reference", "--format", "--max-dt", "--eval-frame",
                          "--calib", "--frames", "--delta", "--no-align", "--loops",
                          "--revisit-radius", "--min-gap", "--plane", "--title", "--out"})
        EXPECT_NE(traj.output.find(o), std::string::npos) << o;
    const CliRun dynamic = run("dynamic --help");
    for (const char* o : {"--changed-is-dynamic", "--min-travel", "--write-static"})
        EXPECT_NE(dynamic.output.find(o), std::string::npos) << o;
    EXPECT_NE(run("reloc -h").output.find("--max-rotation"), std::string::npos);
    const CliRun lifelong = run("lifelong --help");
    for (const char* o : {"--run", "--days", "--wrong", "--new-ground-radius", "--mapped-radius",
                          "--box-margin", "--min-planarity", "--out"})
        EXPECT_NE(lifelong.output.find(o), std::string::npos) << o;
}

TEST(LtmEvalCli, MeshOffsetByHand) {
    const fs::path d = fresh_dir("mesh");
    common::PlyMesh a, b;
    a.vertices = {{0, 0, 0.1f}, {1, 0, 0.1f}, {1, 1, 0.1f}, {0, 1, 0.1f}};
    a.triangles = {{0, 1, 2}, {0, 2, 3}};
    b = a;
    for (auto& v : b.vertices) v.z() = 0;
    common::write_ply((d / "a.ply").string(), a);
    common::write_ply((d / "b.ply").string(), b);
    const CliRun r = run("mesh --mesh " + (d / "a.ply").string() + " --truth " +
                         (d / "b.ply").string() + " --samples 2000 --out " + d.string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(read(d / "metrics.json").find("\"chamfer_l1_m\": 0.1"), std::string::npos);
}

TEST(LtmEvalCli, DynamicOnATinyLabelledRun) {
    // One scan: 3 static points and 1 moving actor; the map keeps the static ones and the actor.
    const fs::path d = fresh_dir("dynamic");
    fs::create_directories(d / "velodyne");
    fs::create_directories(d / "labels");
    common::PointCloud scan;
    scan.points = {{1, 0, 0}, {2, 0, 0}, {3, 0, 0}, {5, 5, 0}};
    common::write_kitti_bin((d / "velodyne" / "000000.bin").string(), scan);
    write_labels(
        (d / "labels" / "000000.label").string(),
        {common::make_label(common::kSimStatic, 0), common::make_label(common::kSimStatic, 0),
         common::make_label(common::kSimStatic, 0),
         common::make_label(common::kSimMovingActor, 1)});
    common::write_kitti_poses((d / "poses.txt").string(), {Eigen::Isometry3d::Identity()});
    common::PlyCloud map;
    map.points = {{1, 0, 0}, {2, 0, 0}, {5, 5, 0}};
    common::write_ply((d / "map.ply").string(), map);
    const CliRun r = run("dynamic --scans " + d.string() + " --map " + (d / "map.ply").string() +
                         " --out " + (d / "out").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string json = read(d / "out" / "metrics.json");
    EXPECT_NE(json.find("\"SA_pct\": 66.6667"), std::string::npos) << json;
    EXPECT_NE(json.find("\"DA_pct\": 0"), std::string::npos) << json;
}

TEST(LtmEvalCli, DynamicPerObject) {
    // Two scans 4 m apart along y. Actor 3 (two points) moves 2 m along x, actor 4 (one point)
    // 0.1 m; the map keeps the static points and actor 4 and none of actor 3.
    const fs::path d = fresh_dir("dynamic_objects");
    fs::create_directories(d / "velodyne");
    fs::create_directories(d / "labels");
    const std::uint32_t ground = common::make_label(common::kSimStatic, 0);
    const std::uint32_t actor3 = common::make_label(common::kSimMovingActor, 3);
    const std::uint32_t actor4 = common::make_label(common::kSimMovingActor, 4);
    common::PoseList poses;
    common::PlyCloud map;
    for (int k = 0; k < 2; ++k) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().y() = 4.0 * k;
        poses.push_back(T);
        const float x3 = 10.0f + 2.0f * static_cast<float>(k);
        const std::vector<Eigen::Vector3f> world = {
            {0, 0, -2}, {x3, 1, 0}, {x3, -1, 0}, {20.0f + 0.1f * static_cast<float>(k), 0, 0}};
        common::PointCloud scan;
        for (const Eigen::Vector3f& p : world) scan.points.push_back(T.inverse().cast<float>() * p);
        const std::string stem = "00000" + std::to_string(k);
        common::write_kitti_bin((d / "velodyne" / (stem + ".bin")).string(), scan);
        write_labels((d / "labels" / (stem + ".label")).string(), {ground, actor3, actor3, actor4});
        map.points.push_back(world[0]);
        map.points.push_back(world[3]);
    }
    common::write_kitti_poses((d / "poses.txt").string(), poses);
    common::write_ply((d / "map.ply").string(), map);
    const CliRun r = run("dynamic --scans " + d.string() + " --map " + (d / "map.ply").string() +
                         " --out " + (d / "out").string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("DA of moving objects >= 1 m: 100.00 % over 1 objects, 4 points"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("\n       3      2     0-1 (2)        2.00         4        100.0\n"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("\n       4      2     0-1 (2)        0.10         2          0.0\n"),
              std::string::npos)
        << r.output;
    const std::string json = read(d / "out" / "metrics.json");
    EXPECT_NE(json.find("\"DA_pct\": 66.6667"), std::string::npos) << json;  // 4 of 6 points
    EXPECT_NE(
        json.find("\"moving_objects\": {\n    \"min_travel_m\": 1,\n    \"all_objects\": 2,"
                  "\n    \"objects\": 1,\n    \"points\": 4,\n    \"removed\": 4,\n    "
                  "\"DA_pct\": 100\n  },\n  \"dynamic_objects\": [\n    {\"id\": 3, \"class\": 2, "
                  "\"first_frame\": 0, \"last_frame\": 1, \"frames\": 2, \"travel_m\": 2, "
                  "\"points\": 4, \"removed\": 4, \"removed_pct\": 100},\n    {\"id\": 4,"),
        std::string::npos)
        << json;
    EXPECT_EQ(json.substr(json.size() - 8), "}\n  ]\n}\n");

    // With --min-travel 0 both actors count: 4 of 6 points.
    const CliRun all = run("dynamic --scans " + d.string() + " --map " + (d / "map.ply").string() +
                           " --min-travel 0");
    EXPECT_NE(all.output.find("DA of moving objects >= 0 m: 66.67 % over 2 objects, 6 points"),
              std::string::npos)
        << all.output;
}

TEST(LtmEvalCli, LoopsAndReloc) {
    const fs::path d = fresh_dir("loops");
    straight_files(d);  // ref.txt: 61 frames along x, no revisit
    write_loop_pairs((d / "loops.txt").string(), {{60, 0, 1.0}});
    const CliRun loops = run("loops --loops " + (d / "loops.txt").string() + " --reference " +
                             (d / "ref.txt").string() + " --out " + d.string());
    ASSERT_EQ(loops.code, 0) << loops.output;
    EXPECT_NE(read(d / "metrics.json").find("\"false_positives\": 1"), std::string::npos);
    EXPECT_TRUE(fs::exists(d / "loops.svg"));

    std::ofstream(d / "reloc.txt") << "10 0.5 1 1 0 0 10.2 0 1 0 0 0 0 1 0\n20 2.0 0\n";
    const CliRun reloc = run("reloc --attempts " + (d / "reloc.txt").string() + " --reference " +
                             (d / "ref.txt").string());
    ASSERT_EQ(reloc.code, 0) << reloc.output;
    EXPECT_NE(reloc.output.find("success_rate"), std::string::npos);
    EXPECT_NE(reloc.output.find(" 0.5\n"), std::string::npos) << reloc.output;
}

}  // namespace
}  // namespace ltm::eval

namespace ltm::eval {
namespace {

// A two-day lifelong run folder: day 0 drives x = 0..39 m (mapped, poses exact), day 1 drives
// y = 30 (new ground) and is lost for its first 10 scans after a kidnapped start. No maps.
fs::path lifelong_run() {
    const fs::path run = fresh_dir("lifelong");
    const Eigen::Isometry3d T_map_world(Eigen::Translation3d(3.0, -2.0, 0.5));
    for (int d = 0; d < 2; ++d) {
        const fs::path day = run / ("day" + std::to_string(d));
        fs::create_directories(day / "truth");
        common::Trajectory truth, published;
        for (int i = 0; i < 40; ++i) {
            common::StampedPose p;
            p.stamp = 86400.0 * d + 0.1 * i;
            p.pose.setIdentity();
            p.pose.translation() = d == 0 ? Eigen::Vector3d(i, 0, 0) : Eigen::Vector3d(i, 30, 0);
            truth.push_back(p);
            if (d == 1 && i < 10) continue;
            p.pose = T_map_world * p.pose;
            published.push_back(p);
        }
        common::write_tum_trajectory((day / "truth/poses_tum.txt").string(), truth);
        common::write_tum_trajectory((day / "map_poses_tum.txt").string(), published);
        if (d == 0) common::write_tum_trajectory((day / "slam_tum.txt").string(), published);
        std::ofstream(day / "truth/kidnaps.txt") << "# frame stamp\n"
                                                 << (d == 1 ? "0 86400\n" : "");
        std::ofstream(day / "truth/objects.txt") << "1 car 5 5 0 0 4.5 1.8 1.5 1\n"
                                                 << (d == 0 ? "2 van 9 5 0 0 5 2 2 1\n" : "");
    }
    return run;
}

TEST(LtmEvalCli, LifelongScoresEachDayInOneAlignment) {
    const fs::path dir = lifelong_run();
    const fs::path out = dir / "score";
    const CliRun r = run("lifelong --run " + dir.string() + " --days 2 --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    // Day 0: every scan, exact; day 1: 30 of 40 scans, the kidnap right after 1.0 s, 40 m new.
    EXPECT_NE(r.output.find("  0    40  100.0  0.000"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("  1    40   75.0  0.000"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1.0s"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("no " + (dir / "day1/next_map").string()), std::string::npos);
    // The same with one scale fitted: exact poses, scale 1.
    EXPECT_NE(r.output.find("0.000 % against the truth, keyframes rmse 0.000 m"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("  1  0.000  0.000   0.00      0"), std::string::npos) << r.output;
    const std::string json = read(out / "metrics.json");
    EXPECT_NE(json.find("\"scans_with_map_pose\": 30"), std::string::npos) << json;
    EXPECT_NE(json.find("\"new_ground_m\": 39"), std::string::npos) << json;
    EXPECT_TRUE(fs::exists(out / "day1.svg"));

    fs::remove(dir / "day1/truth/kidnaps.txt");
    const CliRun bad = run("lifelong --run " + dir.string() + " --days 2");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.output.find("day1/truth/kidnaps.txt: missing"), std::string::npos) << bad.output;
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
}

}  // namespace
}  // namespace ltm::eval
