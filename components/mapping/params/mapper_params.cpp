#include "mapping/params/mapper_params.hpp"

#include "common/core/sensor_detect.hpp"

namespace ltm::mapping {
namespace {

constexpr const char* kKindKey = "scan_context.kind";

places::ScanContextKind parse_kind(runtime::Parameters& params, const std::string& key,
                                   places::ScanContextKind fallback) {
    const std::string name = params.get<std::string>(
        key, fallback == places::ScanContextKind::kMeanVariance ? "mean_variance" : "max_height");
    if (name == "max_height") return places::ScanContextKind::kMaxHeight;
    if (name == "mean_variance") return places::ScanContextKind::kMeanVariance;
    params.fail(key, "expected max_height (Scan Context) or mean_variance (ScanContext++), got '" +
                         name + "'");
}

}  // namespace

MapperConfig load_mapper_config(runtime::Parameters& params, const std::string& prefix,
                                const std::string& default_preset) {
    const std::string pre = prefix.empty() ? "" : prefix + ".";
    const std::string preset = params.get<std::string>(pre + "preset", default_preset);
    MapperConfig config;
    try {
        // auto: the spinning sensors' settings (every spinning preset's are these; the mapping
        // sees keyframes, not scans).
        config = mapper_preset(preset == common::kAutoPreset ? common::kAutoSpinningPreset
                                                             : common::parse_sensor_preset(preset));
    } catch (const std::exception& e) {
        params.fail(pre + "preset", std::string(e.what()) + ", or auto (a spinning sensor)");
    }
    config.scan_context.kind = parse_kind(params, pre + kKindKey, config.scan_context.kind);
    visit_fields(config, [&](const std::string& key, auto& field, const auto& /*rule*/) {
        field = params.get(pre + key, field);
    });
    if (const auto problem = validate(config)) params.fail(pre + problem->key, problem->problem);
    return config;
}

MapperConfig load_mapper_config_file(const std::string& path, const std::string& preset) {
    runtime::Parameters params = runtime::Parameters::from_file(path, "mapping");
    const std::string prefix = params.has("mapping") ? "mapping" : "";
    const std::string preset_key = prefix.empty() ? "preset" : "mapping.preset";
    if (!preset.empty() && params.has(preset_key))
        params.fail(preset_key, "--preset and the config's preset both given");
    MapperConfig config = load_mapper_config(params, prefix, preset.empty() ? "hdl64" : preset);
    params.check_all_used();
    return config;
}

}  // namespace ltm::mapping
