#pragma once
// `ltm_sim SCENARIO.yaml [--seed N] [--session K] [--frames A:B] [--sensor NAME]
// [--format kitti|pcd] [--quiet] --out DIR`: one session of a scenario written as a KITTI-layout
// folder (or PCD scans with per-point time) with its ground truth.
#include <cstdint>
#include <limits>
#include <string>

#include "simulator/core/scenario.hpp"

namespace CLI {
class App;
}

namespace ltm::sim::cli {

struct SimRunOptions {
    std::string scenario;  // YAML file
    bool has_seed = false;
    std::uint64_t seed = 0;
    int session = 0;
    std::size_t first = 0;  // --frames A:B (B exclusive)
    std::size_t last = std::numeric_limits<std::size_t>::max();
    std::string sensor;  // preset replacing the scenario's sensor (mount height and ego box kept)
    // Scan files: "kitti" (velodyne/NNNNNN.bin, x y z intensity) or "pcd" (Scans/NNNNNN.pcd,
    // x y z intensity and, for raw sweeps, per-point time t).
    std::string format = "kitti";
    std::string out;
    bool quiet = false;  // no summary and no progress
    // Only the truth files (times, poses, objects, changes, actors, kidnaps): no scans, labels
    // or truth mesh; what a benchmark needs to score a session the host ran.
    bool truth_only = false;
    // The robot's motion sensors (proprio_files.hpp): IMU and wheel odometry rates [Hz], 0: none.
    double imu_rate = 200.0;
    double wheel_rate = 50.0;
    // Keep every Nth point of each scan (a sparser sensor of the same pattern; labels follow).
    std::size_t point_stride = 1;
};

// Declares ltm_sim's command line on `app`: the scenario, --seed, --session, --frames, --sensor,
// --format, --truth-only, --quiet and --out, filling `options` when the app parses.
void add_sim_options(CLI::App& app, SimRunOptions& options);
// The --seed N and --frames A:B options alone (other tools that run a scenario use them).
void add_seed_option(CLI::App& app, SimRunOptions& options);
void add_frames_option(CLI::App& app, SimRunOptions& options, const std::string& help);

// Loads the scenario with the options applied (seed, sensor). Throws ScenarioError.
ScenarioConfig load_with_options(const SimRunOptions& options);

// Runs and writes the folder. Returns the process exit code; errors go to stderr as one line.
int run_sim(const SimRunOptions& options);
int sim_main(int argc, char** argv);

}  // namespace ltm::sim::cli
