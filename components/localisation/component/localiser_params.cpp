#include "localisation/component/localiser_params.hpp"

#include <stdexcept>

#include "common/core/sensor_detect.hpp"

namespace ltm::localisation {

common::SensorPreset load_sensor_preset(runtime::Parameters& params,
                                        const std::string& default_preset) {
    const std::string name = params.get<std::string>("preset", default_preset);
    try {
        return common::parse_sensor_preset(name);
    } catch (const std::invalid_argument& e) {
        params.fail("preset", e.what());
    }
}

std::optional<common::SensorPreset> load_sensor_preset_or_auto(runtime::Parameters& params,
                                                               const std::string& default_preset) {
    const std::string name = params.get<std::string>("preset", default_preset);
    if (name == common::kAutoPreset) return std::nullopt;
    try {
        return common::parse_sensor_preset(name);
    } catch (const std::invalid_argument& e) {
        params.fail("preset", std::string(e.what()) + ", or auto: told from the scans");
    }
}

LocaliserConfig load_localiser_config(runtime::Parameters& params, common::SensorPreset preset) {
    LocaliserConfig config = localiser_preset(preset);
    visit_fields(config, [&](const std::string& key, auto& field, const auto& /*rule*/) {
        field = params.get(key, field);
    });
    if (const auto problem = validate(config)) params.fail(problem->key, problem->problem);
    return config;
}

}  // namespace ltm::localisation
