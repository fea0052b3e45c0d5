#pragma once
// The ltm_eval subcommands: each takes the arguments after its name, prints its numbers and
// returns the process exit code. They throw UsageError or common::IoError on bad input.
#include <string>
#include <vector>

namespace ltm::eval::cli {

int run_traj(const std::vector<std::string>& args);
int run_dynamic(const std::vector<std::string>& args);
int run_mesh(const std::vector<std::string>& args);
int run_loops(const std::vector<std::string>& args);
int run_reloc(const std::vector<std::string>& args);

extern const char* const kTrajUsage;
extern const char* const kDynamicUsage;
extern const char* const kMeshUsage;
extern const char* const kLoopsUsage;
extern const char* const kRelocUsage;

}  // namespace ltm::eval::cli
