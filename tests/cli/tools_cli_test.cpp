// Every command-line tool as a user runs it: a bad command line gives one line
// `tool: --flag: problem` on stderr and exit code 2, and --help lists every option (exit 0).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "host/process.hpp"

namespace ltm::tests {
namespace {

struct Outcome {
    int code;
    std::string out, err;
};

Outcome run_tool(const std::string& tool, const std::vector<std::string>& args) {
    std::vector<std::string> argv{std::string(LTM_BINARY_DIR) + "/bin/" + tool};
    argv.insert(argv.end(), args.begin(), args.end());
    const std::string log = testing::TempDir() + "ltm_tools_cli_" + std::to_string(::getpid());
    Process p(argv, log);
    const int code = p.wait(60.0);
    return {code, p.out(), p.err()};
}

struct BadLine {
    std::string tool;
    std::vector<std::string> args;
    std::string line;  // on stderr
};

// For each tool: an unknown option, an option without its value, a value of the wrong type.
const std::vector<BadLine> kBadLines = {
    {"ltm_eval", {"traj", "--estimate", "e", "--bogus"}, "ltm_eval traj: --bogus: unknown option"},
    {"ltm_eval",
     {"traj", "--reference", "r", "--estimate"},
     "ltm_eval traj: --estimate: needs a value"},
    {"ltm_eval",
     {"mesh", "--mesh", "a", "--truth", "b", "--samples", "many"},
     "ltm_eval mesh: --samples: expected a non-negative integer, got 'many'"},
    {"ltm_sim", {"s.yaml", "--out", "d", "--bogus"}, "ltm_sim: --bogus: unknown option"},
    {"ltm_sim", {"s.yaml", "--out"}, "ltm_sim: --out: needs a value"},
    {"ltm_sim",
     {"s.yaml", "--out", "d", "--session", "one"},
     "ltm_sim: --session: expected an integer, got 'one'"},
    {"ltm_sim_bench", {"--bogus"}, "ltm_sim_bench: --bogus: unknown option"},
    {"ltm_sim_bench", {"--scans"}, "ltm_sim_bench: --scans: needs a value"},
    {"ltm_sim_bench", {"--scans", "x"}, "ltm_sim_bench: --scans: expected an integer, got 'x'"},
    {"ltm_sim_compare", {"--bogus", "1"}, "ltm_sim_compare: --bogus: unknown option"},
    {"ltm_sim_compare", {"--stride"}, "ltm_sim_compare: --stride: needs a value"},
    {"ltm_sim_compare",
     {"--stride", "x"},
     "ltm_sim_compare: --stride: expected a non-negative integer, got 'x'"},
    {"ltm_bench_odometry", {"dir", "--bogus"}, "ltm_bench_odometry: --bogus: unknown option"},
    {"ltm_bench_odometry", {"dir", "--threads"}, "ltm_bench_odometry: --threads: needs a value"},
    {"ltm_bench_odometry",
     {"dir", "--threads", "2.5"},
     "ltm_bench_odometry: --threads: expected an integer, got '2.5'"},
    {"ltm_bench_slam", {"dir", "--bogus"}, "ltm_bench_slam: --bogus: unknown option"},
    {"ltm_bench_slam", {"dir", "--max-frames"}, "ltm_bench_slam: --max-frames: needs a value"},
    {"ltm_bench_slam",
     {"--graph-bench", "x"},
     "ltm_bench_slam: --graph-bench: expected a non-negative integer, got 'x'"},
    {"ltm_bench_slam",
     {"--scenario", "s.yaml", "--poses", "p.txt"},
     "ltm_bench_slam: --poses: needs a scan folder DIR (not --scenario or --graph-bench)"},
    {"ltm_bench_slam",
     {"dir", "--calib", "c.txt"},
     "ltm_bench_slam: --calib: needs --reference or --poses"},
    {"ltm_mcap", {"info", "f.mcap", "--bogus"}, "ltm_mcap info: --bogus: unknown option"},
    {"ltm_mcap", {"recover", "f.mcap", "-o"}, "ltm_mcap recover: --output: needs a value"},
    {"ltm_mcap",
     {"write-test-file", "f.mcap", "--messages", "x"},
     "ltm_mcap write-test-file: --messages: expected a non-negative integer, got 'x'"},
    {"ltm_mcap_bench", {"--bogus"}, "ltm_mcap_bench: --bogus: unknown option"},
    {"ltm_site", {"versions", "site", "--bogus"}, "ltm_site versions: --bogus: unknown option"},
    {"ltm_site",
     {"import", "site", "--keep", "0", "--map", "m"},
     "ltm_site import: --keep: must be at least 1, not 0"},
    {"ltm_site",
     {"anchor", "site"},
     "ltm_site anchor: give --points FILE or --transform X Y Z ROLL PITCH YAW"},
    // It read its options in pairs and dropped a trailing one: this ran the 10 s benchmark.
    {"ltm_mcap_bench", {"--frames", "0", "--seconds"}, "ltm_mcap_bench: --seconds: needs a value"},
    {"ltm_mcap_bench",
     {"--seconds", "soon"},
     "ltm_mcap_bench: --seconds: expected a number, got 'soon'"},
    {"ltm_bench_dds", {"--bogus"}, "ltm_bench_dds: --bogus: unknown option"},
    {"ltm_bench_dds", {"--rate", "20", "--points"}, "ltm_bench_dds: --points: needs a value"},
    {"ltm_bench_dds",
     {"--count", "many"},
     "ltm_bench_dds: --count: expected a non-negative integer, got 'many'"},
    {"ltm_host", {"x.yaml", "--bogus"}, "ltm_host: --bogus: unknown option"},
    {"ltm_host", {"x.yaml", "--set"}, "ltm_host: --set: needs a value"},
    {"ltm_host",
     {"x.yaml", "--log-level", "loud"},
     "ltm_host: --log-level: must be debug|info|warn|error, not 'loud'"},
};

TEST(ToolsCli, BadCommandLinesGiveOneLineAndExitCode2) {
    for (const auto& c : kBadLines) {
        const Outcome o = run_tool(c.tool, c.args);
        EXPECT_EQ(o.code, 2) << c.line;
        EXPECT_EQ(o.err, c.line + "\n");
        EXPECT_EQ(o.out, "") << c.line;
    }
}

struct Help {
    std::vector<std::string> args;
    std::vector<std::string> options;
};

TEST(ToolsCli, HelpListsEveryOption) {
    const std::vector<std::pair<std::string, Help>> tools = {
        {"ltm_eval", {{"--help"}, {"traj", "dynamic", "mesh", "loops", "reloc"}}},
        {"ltm_eval",
         {{"mesh", "--help"},
          {"--mesh", "--truth", "--samples", "--threshold", "--seed", "--out"}}},
        {"ltm_eval",
         {{"loops", "--help"},
          {"--loops", "--reference", "--match-reference", "--reference-frame", "--calib",
           "--revisit-radius", "--min-gap", "--estimate", "--out"}}},
        {"ltm_eval",
         {{"reloc", "--help"},
          {"--attempts", "--reference", "--reference-frame", "--calib", "--max-translation",
           "--max-rotation", "--out"}}},
        {"ltm_sim",
         {{"--help"},
          {"SCENARIO", "--seed", "--session", "--frames", "--sensor", "--quiet", "--out"}}},
        {"ltm_sim_bench", {{"--help"}, {"--scenario", "--scans", "--sensors"}}},
        {"ltm_sim_compare",
         {{"--help"}, {"--kitti", "--kitti-more", "--scenario", "--seed", "--frames", "--stride"}}},
        {"ltm_bench_odometry",
         {{"--help"},
          {"DIR", "--threads", "--out", "--reference", "--calib", "--preset", "--config",
           "--max-frames", "--frame-log"}}},
        {"ltm_bench_slam",
         {{"--help"},
          {"DIR", "--reference", "--calib", "--out", "--preset", "--config", "--mapping-config",
           "--max-frames", "--snapshot-every", "--pairs", "--session", "--scenario", "--laps",
           "--true-poses", "--graph-bench", "--poses"}}},
        {"ltm_mcap", {{"--help"}, {"info", "verify", "recover", "manifest", "write-test-file"}}},
        {"ltm_mcap",
         {{"write-test-file", "--help"},
          {"OUT", "--manifest", "--compression", "--chunk-size", "--messages"}}},
        {"ltm_mcap_bench", {{"--help"}, {"--frames", "--seconds", "--out", "--kitti"}}},
        {"ltm_site", {{"--help"}, {"versions", "check", "import", "anchor"}}},
        {"ltm_site", {{"import", "--help"}, {"SITE", "--map", "--maintained", "--keep"}}},
        {"ltm_bench_dds", {{"--help"}, {"--points", "--count", "--rate"}}},
        {"ltm_host",
         {{"--help"},
          {"LAUNCH", "--set", "--check", "--log-level", "--list-components", "--list-types"}}},
    };
    for (const auto& [tool, help] : tools) {
        const Outcome o = run_tool(tool, help.args);
        EXPECT_EQ(o.code, 0) << tool;
        EXPECT_EQ(o.err, "") << tool;
        EXPECT_NE(o.out.find("Usage: " + tool), std::string::npos) << o.out;
        for (const auto& option : help.options)
            EXPECT_NE(o.out.find(option), std::string::npos) << tool << " " << option << "\n"
                                                             << o.out;
    }
}

// A map from given poses (ltm_bench_slam DIR --poses P): poses that do not fit the scans are one
// line on stderr and exit code 1, before anything is built.
TEST(ToolsCli, BenchSlamRefusesGivenPosesThatDoNotFit) {
    const std::string dir = testing::TempDir() + "ltm_given_poses_" + std::to_string(::getpid());
    std::filesystem::create_directories(dir + "/velodyne");
    for (const char* scan : {"000000.bin", "000001.bin", "000002.bin"}) {
        std::ofstream f(dir + "/velodyne/" + scan, std::ios::binary);
        const float point[4] = {10.0f, 2.0f, 0.5f, 1.0f};
        for (int i = 0; i < 100; ++i) f.write(reinterpret_cast<const char*>(point), sizeof(point));
    }
    const std::string pose = "1 0 0 0 0 1 0 0 0 0 1 0\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {pose + pose, "2 poses for 3 scans: one pose a scan is needed"},
        {pose + "1 0 0 0 0 1 0 0 0 0 1\n" + pose, "line 2: a KITTI pose needs 12 numbers"},
        {pose + "1 0 0 nan 0 1 0 0 0 0 1 0\n" + pose, "line 2: a KITTI pose needs 12 numbers"},
        {pose + "2 0 0 0 0 1 0 0 0 0 1 0\n" + pose,
         "pose 1 (the pose of scan 1) is not a finite rigid transform"},
    };
    const std::string poses = dir + "/poses.txt";
    for (const auto& [text, problem] : cases) {
        std::ofstream(poses, std::ios::trunc) << text;
        const Outcome o =
            run_tool("ltm_bench_slam", {dir, "--poses", poses, "--out", dir + "/out"});
        EXPECT_EQ(o.code, 1) << problem;
        EXPECT_EQ(o.err, "ltm_bench_slam: " + poses + ": " + problem + "\n");
        EXPECT_FALSE(std::filesystem::exists(dir + "/out")) << problem;
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ltm::tests
