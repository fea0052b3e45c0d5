// ltm_eval: evaluation of ltm runs (trajectories, dynamic removal, meshes, loops,
// relocalisation, lifelong runs) against ground truth. A thin front end over ltm_evaluation_core.
#include <iostream>
#include <map>
#include <string>

#include "evaluation/cli/commands.hpp"

int main(int argc, char** argv) {
    using namespace ltm::eval::cli;
    namespace cli = ltm::common::cli;
    CLI::App app{"Evaluation of ltm runs against ground truth (ltm_eval COMMAND --help)",
                 "ltm_eval"};
    cli::configure(app);
    app.require_subcommand(1);
    const std::map<std::string, Run> runs = {
        {"traj", add_traj(app)},    {"dynamic", add_dynamic(app)}, {"mesh", add_mesh(app)},
        {"loops", add_loops(app)},  {"reloc", add_reloc(app)},     {"lifelong", add_lifelong(app)},
        {"report", add_report(app)}};
    if (const int code = cli::parse(app, argc, argv); code >= 0) return code;
    try {
        return runs.at(app.get_subcommands().front()->get_name())();
    } catch (const UsageError& e) {
        return cli::usage_error(app, e);
    } catch (const std::exception& e) {
        std::cerr << cli::tool_name(app) << ": " << e.what() << "\n";
        return 1;
    }
}
