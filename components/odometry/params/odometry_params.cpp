#include "odometry/params/odometry_params.hpp"

#include "common/core/sensor_detect.hpp"

namespace ltm::odometry {

std::optional<common::SensorPreset> load_odometry_preset(runtime::Parameters& params,
                                                         const std::string& prefix,
                                                         const std::string& default_preset) {
    const std::string key = prefix.empty() ? "preset" : prefix + ".preset";
    const std::string name = params.get<std::string>(key, default_preset);
    if (name == common::kAutoPreset) return std::nullopt;
    try {
        return common::parse_sensor_preset(name);
    } catch (const std::invalid_argument& e) {
        params.fail(key, std::string(e.what()) + ", or auto: told from the scans");
    }
}

OdometryConfig load_odometry_config_for(runtime::Parameters& params, const std::string& prefix,
                                        common::SensorPreset preset) {
    const std::string pre = prefix.empty() ? "" : prefix + ".";
    OdometryConfig config = preset_config(preset);
    visit_fields(config, [&](const std::string& key, auto& field, const auto& /*rule*/) {
        field = params.get(pre + key, field);
    });
    if (const auto problem = validate(config)) params.fail(pre + problem->key, problem->problem);
    return config;
}

OdometryConfig load_odometry_config(runtime::Parameters& params, const std::string& prefix,
                                    const std::string& default_preset) {
    const auto preset = load_odometry_preset(params, prefix, default_preset);
    if (!preset)
        params.fail(prefix.empty() ? "preset" : prefix + ".preset",
                    "auto is decided on the scans (the odometry component): name a preset here");
    return load_odometry_config_for(params, prefix, *preset);
}

OdometryConfig load_odometry_config_file(const std::string& path, const std::string& preset) {
    runtime::Parameters params = runtime::Parameters::from_file(path, "odometry");
    const std::string prefix = params.has("odometry") ? "odometry" : "";
    const std::string preset_key = prefix.empty() ? "preset" : "odometry.preset";
    if (!preset.empty() && params.has(preset_key))
        params.fail(preset_key, "--preset and the config's preset both given");
    OdometryConfig config = load_odometry_config(params, prefix, preset.empty() ? "hdl64" : preset);
    params.check_all_used();
    return config;
}

}  // namespace ltm::odometry
