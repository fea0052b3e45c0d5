#pragma once
// The ltm_eval subcommands: each declares its options on a subcommand of `app` and returns the
// function that runs it once the command line is parsed (it prints its numbers and returns the
// exit code). They throw common::cli::UsageError or common::IoError on bad input.
#include <functional>

#include "common/cli/cli.hpp"

namespace ltm::eval::cli {

using common::cli::UsageError;
using Run = std::function<int()>;

Run add_traj(CLI::App& app);
Run add_dynamic(CLI::App& app);
Run add_mesh(CLI::App& app);
Run add_loops(CLI::App& app);
Run add_reloc(CLI::App& app);
Run add_lifelong(CLI::App& app);
Run add_report(CLI::App& app);

}  // namespace ltm::eval::cli
