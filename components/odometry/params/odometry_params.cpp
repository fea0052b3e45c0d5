#include "odometry/params/odometry_params.hpp"

namespace ltm::odometry {

OdometryConfig load_odometry_config(runtime::Parameters& params, const std::string& prefix,
                                    const std::string& default_preset) {
    const std::string pre = prefix.empty() ? "" : prefix + ".";
    const std::string preset = params.get<std::string>(pre + "preset", default_preset);
    OdometryConfig config;
    try {
        config = preset_config(common::parse_sensor_preset(preset));
    } catch (const std::invalid_argument& e) {
        params.fail(pre + "preset", e.what());
    }
    visit_fields(config, [&](const std::string& key, auto& field, const auto& /*rule*/) {
        field = params.get(pre + key, field);
    });
    if (const auto problem = validate(config)) params.fail(pre + problem->key, problem->problem);
    return config;
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
