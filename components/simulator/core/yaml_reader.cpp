#include "simulator/core/yaml_reader.hpp"

#include "simulator/core/scenario.hpp"

namespace ltm::sim {

void YamlReader::fail(const YAML::Node& at, const std::string& key,
                      const std::string& problem) const {
    const YAML::Mark mark = at.IsDefined() ? at.Mark() : YAML::Mark::null_mark();
    const std::string line = mark.line >= 0 ? ":" + std::to_string(mark.line + 1) : "";
    throw ScenarioError(source_ + line + ": " + key + ": " + problem);
}

void YamlReader::expect_map(const YAML::Node& node, const std::string& key,
                            std::initializer_list<const char*> allowed) const {
    if (!node || node.IsNull()) return;
    if (!node.IsMap()) fail(node, key, "expected a map of keys");
    for (auto it = node.begin(); it != node.end(); ++it) {
        if (!it->first.IsScalar()) fail(it->first, key, "expected plain names as keys");
        const std::string name = it->first.as<std::string>();
        bool ok = false;
        for (const char* a : allowed) ok = ok || name == a;
        if (ok) continue;
        std::string list;
        for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(it->first, join(key, name.c_str()), "unknown key (allowed here: " + list + ")");
    }
}

void YamlReader::expect_sequence(const YAML::Node& node, const std::string& key) const {
    if (!node.IsSequence()) fail(node, key, "expected a list");
}

template <typename T>
bool YamlReader::scalar(const YAML::Node& map, const char* name, const std::string& key, T& out,
                        const char* expected) const {
    if (!map || !map.IsMap()) return false;
    const YAML::Node n = map[name];
    if (!n) return false;
    const std::string k = join(key, name);
    if (!n.IsScalar()) fail(n, k, std::string("expected ") + expected);
    try {
        out = n.as<T>();
    } catch (const YAML::Exception&) {
        fail(n, k, std::string("expected ") + expected + ", got '" + n.Scalar() + "'");
    }
    return true;
}

bool YamlReader::get(const YAML::Node& m, const char* n, const std::string& k, double& out) const {
    return scalar(m, n, k, out, "a number");
}
bool YamlReader::get(const YAML::Node& m, const char* n, const std::string& k, int& out) const {
    return scalar(m, n, k, out, "an integer");
}
bool YamlReader::get(const YAML::Node& m, const char* n, const std::string& k,
                     std::uint64_t& out) const {
    return scalar(m, n, k, out, "a non-negative integer");
}
bool YamlReader::get(const YAML::Node& m, const char* n, const std::string& k, bool& out) const {
    return scalar(m, n, k, out, "true or false");
}
bool YamlReader::get(const YAML::Node& m, const char* n, const std::string& k,
                     std::string& out) const {
    return scalar(m, n, k, out, "a string");
}

std::vector<double> YamlReader::numbers(const YAML::Node& node, const std::string& key,
                                        std::size_t min_len, std::size_t max_len) const {
    if (!node.IsSequence()) fail(node, key, "expected a list of numbers");
    if (node.size() < min_len || node.size() > max_len) {
        fail(node, key,
             min_len == max_len ? "expected " + std::to_string(min_len) + " numbers"
                                : "expected " + std::to_string(min_len) + " to " +
                                      std::to_string(max_len) + " numbers");
    }
    std::vector<double> out;
    for (std::size_t i = 0; i < node.size(); ++i) {
        try {
            out.push_back(node[i].as<double>());
        } catch (const YAML::Exception&) {
            fail(node[i], index(key, i), "expected a number");
        }
    }
    return out;
}

bool YamlReader::get_numbers(const YAML::Node& map, const char* name, const std::string& key,
                             std::size_t length, std::vector<double>& out) const {
    if (!map || !map.IsMap() || !map[name]) return false;
    out = numbers(map[name], join(key, name), length ? length : 1, length ? length : 1000000);
    return true;
}

}  // namespace ltm::sim
