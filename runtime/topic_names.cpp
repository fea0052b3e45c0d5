#include "runtime/topic_names.hpp"

#include <cctype>

namespace ltm::runtime {

std::string normalise_namespace(const std::string& ns) {
    std::string out = ns;
    while (!out.empty() && out.back() == '/') out.pop_back();
    if (!out.empty() && out[0] != '/') out = "/" + out;
    return out;
}

std::string resolve_name(const std::string& name, const std::string& ns,
                         const std::string& component, std::string& error) {
    error.clear();
    if (name.empty()) {
        error = "empty topic name";
        return "";
    }
    std::string abs;
    if (name[0] == '/') {
        abs = name;
    } else if (name.rfind("~/", 0) == 0) {
        abs = normalise_namespace(ns) + "/" + component + "/" + name.substr(2);
    } else if (name[0] == '~') {
        error = "'" + name + "': '~' must be followed by '/'";
        return "";
    } else {
        abs = normalise_namespace(ns) + "/" + name;
    }
    // ROS names: alphanumerics, '_' and '/' separators; no empty tokens, tokens not starting with a
    // digit.
    bool token_start = true;
    for (std::size_t i = 0; i < abs.size(); ++i) {
        const char c = abs[i];
        if (c == '/') {
            if (i > 0 && abs[i - 1] == '/') {
                error = "'" + name + "': empty name token";
                return "";
            }
            token_start = true;
            continue;
        }
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) {
            error =
                "'" + name + "': character '" + std::string(1, c) + "' not allowed in a topic name";
            return "";
        }
        if (token_start && std::isdigit(static_cast<unsigned char>(c))) {
            error = "'" + name + "': a name token cannot start with a digit";
            return "";
        }
        token_start = false;
    }
    if (abs.size() > 1 && abs.back() == '/') {
        error = "'" + name + "': trailing '/'";
        return "";
    }
    return abs;
}

std::string dds_topic_name(const std::string& absolute_name) { return "rt" + absolute_name; }

}  // namespace ltm::runtime
