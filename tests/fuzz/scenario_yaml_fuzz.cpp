// Fuzz target: scenario files (simulator/core/scenario_yaml), parsed from memory.
// Promise: a validated ScenarioConfig or a one-line ScenarioError; no other exception.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_util.hpp"
#include "simulator/core/scenario_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        ltm::sim::parse_scenario(text, "fuzz.yaml", ltm::fuzz::scratch_dir());
    } catch (const ltm::sim::ScenarioError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    return 0;
}
