// ltm_eval: evaluation of ltm runs (trajectories, dynamic removal, meshes, loops,
// relocalisation) against ground truth. A thin front end over ltm_evaluation_core.
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "evaluation/cli/args.hpp"
#include "evaluation/cli/commands.hpp"

namespace {

using namespace ltm::eval::cli;

struct Command {
    const char* name;
    int (*run)(const std::vector<std::string>&);
    const char* const* usage;
    const char* summary;
};

const Command kCommands[] = {
    {"traj", run_traj, &kTrajUsage, "trajectory: ATE, RPE, KITTI metric, figures"},
    {"dynamic", run_dynamic, &kDynamicUsage, "dynamic-object removal: SA, DA, AA"},
    {"mesh", run_mesh, &kMeshUsage, "mesh accuracy, completeness, Chamfer-L1"},
    {"loops", run_loops, &kLoopsUsage, "place recognition: precision, recall, F1"},
    {"reloc", run_reloc, &kRelocUsage, "relocalisation success rate and time"},
};

void print_usage(std::ostream& out) {
    out << "usage: ltm_eval <command> [options]   (ltm_eval <command> --help for its options)\n";
    for (const auto& c : kCommands)
        out << "  " << c.name << std::string(10 - std::strlen(c.name), ' ') << c.summary << "\n";
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        print_usage(argc < 2 ? std::cerr : std::cout);
        return argc < 2 ? 2 : 0;
    }
    const std::string name = argv[1];
    const std::vector<std::string> args(argv + 2, argv + argc);
    for (const auto& c : kCommands) {
        if (name != c.name) continue;
        for (const auto& a : args)
            if (a == "--help" || a == "-h") {
                std::cout << *c.usage;
                return 0;
            }
        try {
            return c.run(args);
        } catch (const UsageError& e) {
            std::cerr << "ltm_eval " << name << ": " << e.what() << "\n" << *c.usage;
            return 2;
        } catch (const std::exception& e) {
            std::cerr << "ltm_eval " << name << ": " << e.what() << "\n";
            return 1;
        }
    }
    std::cerr << "ltm_eval: unknown command '" << name << "'\n";
    print_usage(std::cerr);
    return 2;
}
