#pragma once
// The sensor a folder of simulated scans was rendered with, and the sensor preset that goes with
// it: `ltm_sim` notes its model at the end of the folder's scenario.yaml ("# ltm_sim run: ...,
// sensor os1_64, ..."), and every preset row names the simulator model it describes. The budget
// benchmark sets the presets of the launch config's components from it, so the presets follow
// the data and no run needs to be told which preset its scans want.
#include <string>

#include "common/core/sensor_preset.hpp"

namespace ltm::bench {

// The model in the "# ltm_sim run:" line of `scenario_text`; "" if there is no such line.
std::string sim_model_of_note(const std::string& scenario_text);

// DIR/scenario.yaml's model. Throws std::runtime_error naming the file if it is missing or has no
// ltm_sim line.
std::string scans_sim_model(const std::string& dir);

// The preset whose simulator model is `model` ("os1_64" -> kOs1_64). Throws std::runtime_error
// naming the models that have one.
common::SensorPreset preset_of_sim_model(const std::string& model);

}  // namespace ltm::bench
