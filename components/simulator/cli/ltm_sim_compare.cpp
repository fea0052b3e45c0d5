// ltm_sim_compare: simulated HDL-64E street scans beside real KITTI scans, all computed the same
// way (points a scan, points per ring, elevation per ring, range histogram, intensities).
#include <iostream>
#include <string>
#include <vector>

#include "common/cli/cli.hpp"
#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "simulator/cli/scan_stats.hpp"
#include "simulator/cli/sim_run.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"

namespace {

const char* kDescription =
    "Simulated HDL-64E street scans beside real KITTI scans, all computed the same way. Columns:\n"
    "the real scans of --kitti (the shared KITTI 00 snippet, frames 0-15); those of --kitti-more\n"
    "(the shared 04, 05, 07 snippets: how much real streets differ); the simulated scans\n"
    "--frames (the same stretch of the KITTI 00 path, which scenarios/kitti00_path.yaml\n"
    "drives); every --stride-th simulated scan of the route (the typical street).";

}  // namespace

int main(int argc, char** argv) {
    using namespace ltm;
    const std::string shared = LTM_SOURCE_DIR "/../shared/data/kitti/sequences/";
    std::string kitti = shared + "00";
    std::string more = shared + "04," + shared + "05," + shared + "07";
    sim::cli::SimRunOptions options;
    options.scenario = LTM_SOURCE_DIR "/components/simulator/scenarios/kitti00_path.yaml";
    options.first = 0;
    options.last = 16;
    std::size_t stride = 100;
    CLI::App app{kDescription, "ltm_sim_compare"};
    common::cli::configure(app);
    app.add_option("--kitti", kitti, "KITTI sequence folder of the real scans");
    app.add_option("--kitti-more", more, "more real sequence folders, comma-separated");
    app.add_option("--scenario", options.scenario, "the simulated scenario");
    sim::cli::add_seed_option(app, options);
    sim::cli::add_frames_option(app, options, "simulated scans A..B-1 (default 0:16)");
    app.add_option("--stride", stride, "every N-th scan of the route")
        ->check(common::cli::at_least(1));
    if (const int code = common::cli::parse(app, argc, argv); code >= 0) return code;
    const std::vector<double> edges = {0, 2.5, 5, 7.5, 10, 15, 20, 30, 40, 50, 60, 80, 100};
    try {
        std::vector<sim::cli::ScanStats> real, others, here, along;
        const auto files = common::list_kitti_scans(kitti);
        if (files.empty())
            throw common::IoError(kitti, "no .bin scans (is the shared KITTI data here?)");
        for (const auto& f : files)
            real.push_back(sim::cli::scan_stats(common::read_kitti_bin(f), edges));
        std::size_t n_more = 0;
        for (std::size_t start = 0; start < more.size();) {
            const std::size_t comma = std::min(more.find(',', start), more.size());
            const std::string dir = more.substr(start, comma - start);
            start = comma + 1;
            if (dir.empty()) continue;
            for (const auto& f : common::list_kitti_scans(dir)) {
                others.push_back(sim::cli::scan_stats(common::read_kitti_bin(f), edges));
                ++n_more;
            }
        }

        const sim::ScenarioConfig sc = sim::cli::load_with_options(options);
        const sim::Simulator simulator(sc, options.session);
        sim::SimScan scan;
        for (std::size_t i = options.first; i < std::min(options.last, simulator.num_scans());
             ++i) {
            simulator.scan(i, scan);
            here.push_back(sim::cli::scan_stats(scan.cloud, edges));
        }
        for (std::size_t i = 0; i < simulator.num_scans(); i += stride) {
            simulator.scan(i, scan);
            along.push_back(sim::cli::scan_stats(scan.cloud, edges));
        }
        std::cout << "KITTI: " << files.size() << " real scans from " << kitti << "\n"
                  << "KITTI more: " << n_more << " real scans from " << more << "\n"
                  << "sim here: scans " << options.first << ".." << options.first + here.size() - 1
                  << " of " << sc.name << " (" << sc.sensor.model << ", seed " << sc.seed << ")\n"
                  << "sim route: " << along.size() << " scans, every " << stride << "th of "
                  << simulator.num_scans() << "\n\n"
                  << sim::cli::compare_table(
                         {sim::cli::average_stats(real), sim::cli::average_stats(others),
                          sim::cli::average_stats(here), sim::cli::average_stats(along)},
                         {"KITTI", "KITTI more", "sim here", "sim route"});
    } catch (const sim::ScenarioError& e) {
        std::cerr << "ltm_sim_compare: " << e.what() << "\n";
        return 1;
    } catch (const common::IoError& e) {
        std::cerr << "ltm_sim_compare: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
