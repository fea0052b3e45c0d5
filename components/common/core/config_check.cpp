#include "common/core/config_check.hpp"

#include <cmath>
#include <sstream>

#include "common/core/one_line.hpp"

namespace ltm::common {
namespace {

template <class T>
std::string text_of(const T& value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

}  // namespace

ConfigError::ConfigError(const std::string& key, const std::string& problem)
    : std::invalid_argument(one_line(key + ": " + problem)), key_(key), problem_(problem) {}

ConfigError::ConfigError(const std::string& file, int line, const std::string& key,
                         const std::string& problem)
    : std::invalid_argument(
          one_line(file + ":" + std::to_string(line) + ": " + key + ": " + problem)),
      file_(file),
      line_(line),
      key_(key),
      problem_(problem) {}

ConfigError::ConfigError(const std::string& section, const ConfigProblem& problem)
    : ConfigError(section.empty() ? problem.key : section + "." + problem.key, problem.problem) {}

std::string Rule::range_text() const {
    if (hi_ == kInf) return (lo_open_ ? "> " : ">= ") + text_of(lo_);
    return std::string(kind_ == Kind::kZeroOrRange ? "0 or " : "") + "in " +
           (lo_open_ ? "(" : "[") + text_of(lo_) + ", " + text_of(hi_) + "]";
}

std::string Rule::broken_by(double v) const {
    const bool finite = std::isfinite(v) || (infinity_ok_ && v == kInf);
    switch (kind_) {
        case Kind::kAny:
        case Kind::kNotEmpty:
            return {};
        case Kind::kFinite:
            return finite ? std::string() : "finite";
        case Kind::kRange:
        case Kind::kZeroOrRange:
            break;
    }
    if (kind_ == Kind::kZeroOrRange && v == 0.0) return {};
    const bool above = lo_open_ ? v > lo_ : v >= lo_;
    return finite && above && v <= hi_ ? std::string() : range_text();
}

std::string Rule::broken_by_size(std::size_t size) const {
    return kind_ == Kind::kNotEmpty && size == 0 ? "hold at least one value" : std::string();
}

void ConfigChecker::number(const std::string& key, const std::string& text, double value,
                           const Rule& rule) {
    if (problem_) return;
    const std::string must = rule.broken_by(value);
    if (!must.empty()) problem_ = ConfigProblem{key, "must be " + must + " (got " + text + ")"};
}

void ConfigChecker::operator()(const std::string& key, double value, const Rule& rule) {
    number(key, text_of(value), value, rule);
}

void ConfigChecker::operator()(const std::string& key, int value, const Rule& rule) {
    number(key, std::to_string(value), double(value), rule);
}

void ConfigChecker::operator()(const std::string& key, const std::vector<double>& value,
                               const Rule& rule) {
    const std::string must = rule.broken_by_size(value.size());
    require(must.empty(), key, "must " + must);
}

void ConfigChecker::operator()(const std::string& key, const std::string& value,
                               const OneOf& rule) {
    for (const std::string& name : rule.names) {
        if (value == name) return;
    }
    std::string names;
    for (std::size_t i = 0; i < rule.names.size(); ++i) {
        names += (i == 0 ? "" : i + 1 == rule.names.size() ? " or " : ", ") + rule.names[i];
    }
    require(false, key, "must be " + names + " (got '" + value + "')");
}

void ConfigChecker::require(bool ok, const std::string& key, const std::string& problem) {
    if (!ok && !problem_) problem_ = ConfigProblem{key, problem};
}

void ConfigChecker::include(const std::optional<ConfigProblem>& part, const std::string& prefix) {
    if (part && !problem_) problem_ = ConfigProblem{prefix + part->key, part->problem};
}

void throw_if(const std::optional<ConfigProblem>& problem, const std::string& section) {
    if (problem) throw ConfigError(section, *problem);
}

}  // namespace ltm::common
