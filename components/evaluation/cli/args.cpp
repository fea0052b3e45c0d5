#include "evaluation/cli/args.hpp"

#include <cerrno>
#include <cstdlib>

namespace ltm::eval::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& options,
           const std::set<std::string>& flags) {
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.rfind("--", 0) != 0) throw UsageError("unexpected argument '" + a + "'");
        std::string name = a.substr(2), value;
        const auto eq = name.find('=');
        if (eq != std::string::npos) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
        }
        if (flags.count(name)) {
            if (eq != std::string::npos) throw UsageError("--" + name + " takes no value");
            values_[name] = "1";
        } else if (options.count(name)) {
            if (eq == std::string::npos) {
                if (i + 1 >= argv.size()) throw UsageError("--" + name + " needs a value");
                value = argv[++i];
            }
            values_[name] = value;
        } else {
            throw UsageError("unknown option --" + name);
        }
    }
}

bool Args::has(const std::string& name) const { return values_.count(name) > 0; }

std::string Args::get(const std::string& name, const std::string& fallback) const {
    const auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

std::string Args::required(const std::string& name) const {
    if (!has(name)) throw UsageError("--" + name + " is required");
    return get(name);
}

double Args::number(const std::string& name, double fallback) const {
    if (!has(name)) return fallback;
    const std::string s = get(name);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || errno != 0)
        throw UsageError("--" + name + " needs a number, not '" + s + "'");
    return v;
}

long Args::integer(const std::string& name, long fallback) const {
    if (!has(name)) return fallback;
    const std::string s = get(name);
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno != 0)
        throw UsageError("--" + name + " needs an integer, not '" + s + "'");
    return v;
}

std::string Args::choice(const std::string& name, const std::vector<std::string>& choices,
                         const std::string& fallback) const {
    if (!has(name)) return fallback;
    const std::string v = get(name);
    std::string list;
    for (const auto& c : choices) {
        if (c == v) return v;
        list += (list.empty() ? "" : "|") + c;
    }
    throw UsageError("--" + name + " must be " + list + ", not '" + v + "'");
}

}  // namespace ltm::eval::cli
