#pragma once
// Scenario files (YAML) into ScenarioConfig. The schema is documented in
// components/simulator/scenarios/README.md. Unknown keys are rejected with a message naming the
// key and its line.
#include <string>

#include "simulator/core/scenario.hpp"

namespace ltm::sim {

// Reads a scenario file; relative paths in it are relative to its folder. Throws ScenarioError.
ScenarioConfig load_scenario(const std::string& path);
// Parses scenario text; `source` names it in messages, `base_dir` anchors relative paths.
ScenarioConfig parse_scenario(const std::string& text, const std::string& source,
                              const std::string& base_dir);

}  // namespace ltm::sim
