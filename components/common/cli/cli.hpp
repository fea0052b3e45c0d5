#pragma once
// The command line of every ltm tool: options declared on a CLI::App (CLI11), `--help` generated
// from those declarations, and one error style for every usage error, on one line and exit code 2:
//   tool: --flag: problem
// A tool declares its options, calls parse() and then does its work:
//   CLI::App app{"what the tool does", "ltm_tool"};
//   cli::configure(app);  // before the options: their defaults apply to each
//   app.add_option("--frames", frames, "how many")->check(cli::at_least(1));
//   if (const int code = cli::parse(app, argc, argv); code >= 0) return code;
#include <CLI/CLI.hpp>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace ltm::common::cli {

// A usage error found after parsing (flags that do not go together, a value the tool rejects):
// what() is `--flag: problem` (or just `problem`); the tool reports it with usage_error().
class UsageError : public std::runtime_error {
  public:
    UsageError(const std::string& flag, const std::string& problem);
    explicit UsageError(const std::string& problem);
};

// An App set up the ltm way: `name` is the tool ("ltm_sim"), `description` the first help line.
// Flags refuse a value (`--quiet=1`), and the help lists every option with its default.
void configure(CLI::App& app);

// Parses the command line (argv[0] is the program). Returns -1 to go on, or the exit code once it
// has printed what the user asked for or did wrong: 0 after `--help` (the help of the selected
// command on `out`), 2 after a usage error (one line `tool: --flag: problem` on `err`).
int parse(CLI::App& app, int argc, const char* const* argv);
int parse(CLI::App& app, const std::vector<std::string>& args, std::ostream& out,
          std::ostream& err);

// Prints `tool: problem` for a UsageError raised after parsing (tool: the app, or the selected
// subcommand, as `ltm_eval traj`) and returns 2.
int usage_error(const CLI::App& app, const UsageError& e, std::ostream& err);
int usage_error(const CLI::App& app, const UsageError& e);

// The name errors are reported under: the app's name, then the selected subcommands'.
std::string tool_name(const CLI::App& app);

// Validators with one-line messages: `--f: must be a|b|c, not 'x'`, `--n: must be at least 1`.
CLI::Validator one_of(const std::vector<std::string>& choices);
CLI::Validator at_least(double minimum);
CLI::Validator positive();

}  // namespace ltm::common::cli
