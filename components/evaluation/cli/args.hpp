#pragma once
// A small `--name value` / `--flag` parser for the ltm_eval subcommands.
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace ltm::eval::cli {

// Bad command line: what() is one line for the user.
class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class Args {
  public:
    // `flags` take no value, `options` take one. Anything else is rejected, naming it.
    Args(const std::vector<std::string>& argv, const std::set<std::string>& options,
         const std::set<std::string>& flags);

    bool has(const std::string& name) const;
    std::string get(const std::string& name, const std::string& fallback = "") const;
    std::string required(const std::string& name) const;
    double number(const std::string& name, double fallback) const;
    long integer(const std::string& name, long fallback) const;
    // `name` must be one of `choices` (fallback when absent).
    std::string choice(const std::string& name, const std::vector<std::string>& choices,
                       const std::string& fallback) const;

  private:
    std::map<std::string, std::string> values_;
};

}  // namespace ltm::eval::cli
