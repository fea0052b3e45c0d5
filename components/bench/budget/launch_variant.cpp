#include "bench/budget/launch_variant.hpp"

#include <stdexcept>

namespace ltm::bench {

std::vector<std::string> component_names(const YAML::Node& config) {
    std::vector<std::string> out;
    if (!config["components"] || !config["components"].IsSequence())
        throw std::runtime_error("the launch config has no components list");
    for (const auto& c : config["components"]) out.push_back(c["name"].as<std::string>(""));
    return out;
}

YAML::Node budget_variant(const YAML::Node& config, const VariantOptions& o) {
    YAML::Node out = YAML::Clone(config);
    const auto names = component_names(out);
    YAML::Node components = out["components"];
    if (!o.replace.empty()) {
        bool found = false;
        for (std::size_t i = 0; i < components.size(); ++i) {
            if (components[i]["name"].as<std::string>("") != o.replace) continue;
            YAML::Node player;
            player["name"] = o.replace;
            player["type"] = "kitti_player";
            player["params"]["path"] = o.scans;
            player["params"]["mode"] = "realtime";  // times.txt: the sensor's own rate
            player["params"]["rate"] = 1.0;
            player["params"]["wait_for_readers"] = o.wait_for_readers;
            components[i] = player;
            found = true;
        }
        if (!found) throw std::runtime_error("no component '" + o.replace + "' to replace");
        // Live: the scans on their declared role (sensor: best effort, a slow reader drops).
        if (out["topics"] && out["topics"].IsMap()) {
            out["topics"].remove("points");
            out["topics"].remove("ground_truth");
            if (out["topics"].size() == 0) out.remove("topics");
        }
    }
    if (!o.preset.empty()) {
        for (std::size_t i = 0; i < components.size(); ++i) {
            const std::string type = components[i]["type"].as<std::string>("");
            for (const char* t : kPresetTypes)
                if (type == t) components[i]["params"]["preset"] = o.preset;
        }
    }
    if (!o.probe_file.empty()) {
        YAML::Node probe;
        probe["name"] = "budget_probe";
        probe["type"] = "budget_probe";
        probe["params"]["file"] = o.probe_file;
        for (const auto& input : o.probe_inputs) probe["params"]["inputs"].push_back(input);
        if (!o.probe_pose_topic.empty()) probe["remap"]["pose"] = o.probe_pose_topic;
        components.push_back(probe);
    }
    return out;
}

}  // namespace ltm::bench
