#pragma once
// One way to check a configuration. Each field's rule is stated once, next to the field in its
// config's visit_fields list (`v("voxel_size", c.voxel_size, positive)`); a ConfigChecker walks
// that list and keeps the first {key, problem}; rules across fields follow by hand
// (`k.require(...)`). ConfigError is the one error of a refused configuration: the cores throw it
// with the key, the parameter loader with the file and line the value came from.
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ltm::common {

// A value that breaks a rule: its dotted key (relative to the config checked) and what is wrong.
struct ConfigProblem {
    std::string key;      // "preprocess.max_range"
    std::string problem;  // "must be > 0 (got -1)"
};

// A refused configuration. what() is one line naming the key: "KEY: PROBLEM" for a config built
// in code, "FILE:LINE: KEY: PROBLEM" for a value read from a file (control characters escaped).
class ConfigError : public std::invalid_argument {
  public:
    ConfigError(const std::string& key, const std::string& problem);
    ConfigError(const std::string& file, int line, const std::string& key,
                const std::string& problem);
    // The problem of a config, its key under `section` ("odometry": "odometry.voxel_size").
    ConfigError(const std::string& section, const ConfigProblem& problem);

    const std::string& file() const { return file_; }  // empty when not read from a file
    int line() const { return line_; }
    const std::string& key() const { return key_; }
    const std::string& problem() const { return problem_; }

  private:
    std::string file_;
    int line_ = 0;
    std::string key_, problem_;
};

// The rule of a number (or of a list's length): a range, finite unless or_infinite().
class Rule {
  public:
    enum class Kind : std::uint8_t { kAny, kFinite, kRange, kZeroOrRange, kNotEmpty };
    static constexpr double kInf = std::numeric_limits<double>::infinity();

    constexpr explicit Rule(Kind kind, double lo = -kInf, double hi = kInf, bool lo_open = false)
        : kind_(kind), lo_(lo), hi_(hi), lo_open_(lo_open) {}
    // The same rule, +infinity allowed too (a limit that may be "none").
    constexpr Rule or_infinite() const {
        Rule r = *this;
        r.infinity_ok_ = true;
        return r;
    }
    // What the value must be ("> 0", "in [0, 1]"); empty when `value` keeps the rule.
    std::string broken_by(double value) const;
    // A list of `size` values: "hold at least one value" when it must not be empty.
    std::string broken_by_size(std::size_t size) const;

  private:
    std::string range_text() const;

    Kind kind_;
    double lo_, hi_;
    bool lo_open_;
    bool infinity_ok_ = false;
};

// Text with a fixed set of values.
struct OneOf {
    std::vector<std::string> names;
};

// The rules, for `using namespace common::rules;` in a visit_fields list.
namespace rules {
inline constexpr Rule unchecked{Rule::Kind::kAny};  // switches and values of any size
inline constexpr Rule finite{Rule::Kind::kFinite};
inline constexpr Rule positive{Rule::Kind::kRange, 0.0, Rule::kInf, true};  // finite, > 0
inline constexpr Rule non_negative{Rule::Kind::kRange, 0.0};                // finite, >= 0
inline constexpr Rule unit{Rule::Kind::kRange, 0.0, 1.0};                   // in [0, 1]
inline constexpr Rule not_empty{Rule::Kind::kNotEmpty};                     // a list
constexpr Rule at_least(double lo) { return Rule(Rule::Kind::kRange, lo); }
constexpr Rule above(double lo) { return Rule(Rule::Kind::kRange, lo, Rule::kInf, true); }
constexpr Rule in_range(double lo, double hi) { return Rule(Rule::Kind::kRange, lo, hi); }
constexpr Rule zero_or_in(double lo, double hi) { return Rule(Rule::Kind::kZeroOrRange, lo, hi); }
inline OneOf one_of(std::vector<std::string> names) { return OneOf{std::move(names)}; }
}  // namespace rules

// The visitor of a visit_fields list that checks each field against its rule, then the rules
// across fields by hand; it keeps the first problem.
class ConfigChecker {
  public:
    void operator()(const std::string& key, double value, const Rule& rule);
    void operator()(const std::string& key, int value, const Rule& rule);
    void operator()(const std::string& key, const std::vector<double>& value, const Rule& rule);
    void operator()(const std::string& key, const std::string& value, const OneOf& rule);
    void operator()(const std::string&, bool, const Rule&) {}                // a switch: any value
    void operator()(const std::string&, const std::string&, const Rule&) {}  // free text

    // A rule across fields: when `ok` is false, `key` has `problem`.
    void require(bool ok, const std::string& key, const std::string& problem);
    // The problem of a part of the config, its key under `prefix` ("scan_context.").
    void include(const std::optional<ConfigProblem>& part, const std::string& prefix);

    const std::optional<ConfigProblem>& problem() const { return problem_; }

  private:
    void number(const std::string& key, const std::string& text, double value, const Rule& rule);

    std::optional<ConfigProblem> problem_;
};

// Throws ConfigError(section, problem) when there is a problem.
void throw_if(const std::optional<ConfigProblem>& problem, const std::string& section);

}  // namespace ltm::common
