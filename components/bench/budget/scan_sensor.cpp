#include "bench/budget/scan_sensor.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace ltm::bench {

std::string sim_model_of_note(const std::string& text) {
    const std::string marker = "# ltm_sim run:", key = "sensor ";
    const auto at = text.rfind(marker);
    if (at == std::string::npos) return "";
    const std::string line = text.substr(at, text.find('\n', at) - at);
    // The note is "seed S, session N, frames A:B, sensor MODEL, format F".
    std::size_t k = line.find(", " + key);
    if (k == std::string::npos) return "";
    k += 2 + key.size();
    const auto end = line.find_first_of(", ", k);
    return line.substr(k, end == std::string::npos ? std::string::npos : end - k);
}

std::string scans_sim_model(const std::string& dir) {
    const std::string path = dir + "/scenario.yaml";
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot read (not a folder ltm_sim wrote?)");
    std::stringstream text;
    text << in.rdbuf();
    const std::string model = sim_model_of_note(text.str());
    if (model.empty())
        throw std::runtime_error(path + ": no '# ltm_sim run: ..., sensor MODEL' line");
    return model;
}

common::SensorPreset preset_of_sim_model(const std::string& model) {
    std::string known;
    for (const auto p : common::kSensorPresets) {
        const auto& row = common::sensor_preset_row(p);
        if (model == row.simulator_model) return p;
        known += std::string(known.empty() ? "" : ", ") + row.simulator_model;
    }
    throw std::runtime_error("sensor model '" + model + "' has no preset (presets exist for " +
                             known + ")");
}

}  // namespace ltm::bench
