// ltm_sim_bench: simulator speed per sensor model on one core (the simulator is single-threaded):
// world build time, scans a second and points a scan over scans spread along the route.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "simulator/cli/sim_run.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
    using namespace ltm;
    std::string scenario = LTM_SOURCE_DIR "/components/simulator/scenarios/kitti00_path.yaml";
    std::string sensors = "hdl64e,vlp32c,vlp16,livox_avia";
    int scans = 50;
    CLI::App app{
        "Simulator speed per sensor model on one core: world build time, scans a second "
        "and points a scan",
        "ltm_sim_bench"};
    common::cli::configure(app);
    app.add_option("--scenario", scenario, "the scenario (a street scene by default)");
    app.add_option("--scans", scans, "scans per sensor, spread along the route")
        ->check(common::cli::at_least(1));
    app.add_option("--sensors", sensors, "sensor presets, comma-separated");
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    std::printf("%-12s %10s %12s %12s %12s %10s\n", "sensor", "build [s]", "scans/s", "ms/scan",
                "points/scan", "triangles");
    std::stringstream list(sensors);
    std::string name;
    while (std::getline(list, name, ',')) {
        sim::cli::SimRunOptions o;
        o.scenario = scenario;
        o.sensor = name;
        try {
            const sim::ScenarioConfig sc = sim::cli::load_with_options(o);
            auto t0 = std::chrono::steady_clock::now();
            const sim::Simulator simulator(sc, 0);
            const double build = seconds_since(t0);
            const std::size_t n =
                std::min<std::size_t>(static_cast<std::size_t>(scans), simulator.num_scans());
            const std::size_t stride = std::max<std::size_t>(1, simulator.num_scans() / n);
            sim::SimScan scan;
            double points = 0;
            t0 = std::chrono::steady_clock::now();
            for (std::size_t k = 0; k < n; ++k) {
                simulator.scan(k * stride, scan);
                points += static_cast<double>(scan.cloud.size());
            }
            const double t = seconds_since(t0);
            std::printf("%-12s %10.2f %12.1f %12.1f %12.0f %10zu\n", name.c_str(), build, n / t,
                        1000 * t / n, points / n, simulator.world().static_mesh().num_triangles());
        } catch (const sim::ScenarioError& e) {
            std::cerr << "ltm_sim_bench: " << e.what() << "\n";
            return 1;
        }
    }
    return 0;
}
