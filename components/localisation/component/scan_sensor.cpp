#include "localisation/component/scan_sensor.hpp"

#include <cstdio>
#include <string>
#include <vector>

#include "localisation/component/localiser_params.hpp"
#include "odometry/core/odometry_config.hpp"
#include "odometry/params/odometry_params.hpp"

namespace ltm::localisation {
namespace {

// The odometry's settings as this host's odometry component runs them (its preset and every key it
// is given: an `odometry.voxel_size` override reaches the localisation's preprocessing too), else
// the localisation preset's (no odometry component here, or more than one). A preset `auto` (the
// odometry's or, without one, the localisation's) is the one the scans told (`detected`); none
// yet: empty (asked again on the first scans). Says which in the log.
std::optional<odometry::OdometryConfig> odometry_in_use(
    runtime::ComponentContext& ctx, std::optional<common::SensorPreset> own,
    std::optional<common::SensorPreset> detected) {
    const runtime::LaunchConfig& launch = ctx.launch_config();
    std::vector<const runtime::ComponentSpec*> found;
    for (const runtime::ComponentSpec& c : launch.components)
        if (c.type == "odometry") found.push_back(&c);
    odometry::OdometryConfig oc;
    std::string from;
    if (found.size() == 1) {
        runtime::Parameters params(found[0]->params, launch.file, found[0]->name);
        // As the odometry component reads them (its preset's default: auto).
        const auto preset = odometry::load_odometry_preset(params, "", common::kAutoPreset);
        if (!preset && !detected) return std::nullopt;
        oc = odometry::load_odometry_config_for(params, "", preset ? *preset : *detected);
        from = "odometry component '" + found[0]->name + "'" +
               (preset ? "" : std::string(" (preset auto: ") + to_string(*detected) + ")");
    } else {
        const std::optional<common::SensorPreset> preset = own ? own : detected;
        if (!preset) return std::nullopt;
        oc = odometry::preset_config(*preset);
        from = std::string("preset ") + common::to_string(*preset) + (own ? "" : " (auto)") + " (" +
               (found.empty() ? "no" : std::to_string(found.size())) +
               " odometry components in this host)";
    }
    char text[240];
    std::snprintf(text, sizeof text, "scans preprocessed as by the %s: voxel_size %.3g m",
                  from.c_str(), oc.voxel_size);
    ctx.log().info(text);
    return oc;
}

// The preset this host's one odometry component is named (not auto): the sensor its user told.
// Empty with none, several, or one under auto.
std::optional<common::SensorPreset> odometry_named_preset(runtime::ComponentContext& ctx) {
    const runtime::LaunchConfig& launch = ctx.launch_config();
    const runtime::ComponentSpec* found = nullptr;
    for (const runtime::ComponentSpec& c : launch.components) {
        if (c.type != "odometry") continue;
        if (found) return std::nullopt;
        found = &c;
    }
    if (!found) return std::nullopt;
    runtime::Parameters params(found->params, launch.file, found->name);
    return odometry::load_odometry_preset(params, "", common::kAutoPreset);
}

bool narrow(common::SensorPreset preset) {
    return common::sensor_preset_row(preset).horizontal_fov_deg < 360.0;
}

}  // namespace

ScanSensor::ScanSensor(runtime::ComponentContext& ctx) : ctx_(ctx) {
    auto& p = ctx.params();
    named_ = load_sensor_preset_or_auto(p, common::kAutoPreset);
    // auto: the sensor this host's odometry was named, else the one the first scans tell.
    const std::optional<common::SensorPreset> told = named_ ? named_ : odometry_named_preset(ctx);
    told_ = told.has_value();
    preset_ = told.value_or(common::kAutoSpinningPreset);
    if (!named_ && told) {
        ctx.log().info(std::string("preset auto: the odometry component's preset ") +
                       common::to_string(*told));
    } else if (!named_) {
        ctx.log().info(
            "preset auto: the localiser's and the map's settings of the spinning sensors (hdl64, "
            "vlp32, vlp16 and os1-64 share them) until the first scans tell the sensor: a narrow "
            "one's then (preset narrow), the map reloaded with them before the first scan is "
            "localised");
        narrow_config_ = load_localiser_config(p, common::SensorPreset::kNarrow);
    }
    config_ = load_localiser_config(p, preset_);
    if (const auto oc = odometry_in_use(ctx, named_, std::nullopt))
        preprocessor_.emplace(oc->preprocess, oc->voxel_size);
    // Tracking and global queries take their own samples of the map points.
    if (preprocessor_) preprocessor_->set_map_points_only(true);
}

bool ScanSensor::add(const common::PointCloud& cloud, std::optional<Retune>* retune) {
    if (!detector_.add(cloud)) return false;
    told_ = true;
    const common::SensorPreset detected = detector_.preset();
    ctx_.log().info(detector_.line());
    if (!preprocessor_) {
        const auto oc = odometry_in_use(ctx_, named_, detected);
        preprocessor_.emplace(oc->preprocess, oc->voxel_size);
        preprocessor_->set_map_points_only(true);
    }
    if (!narrow_config_ || !narrow(detected) || !detector_.detected()) return true;
    *retune = Retune{detected, *narrow_config_};
    narrow_config_.reset();  // once
    ctx_.log().info(std::string("preset auto: the scans are a narrow sensor's: the localiser's and "
                                "the map's settings of preset ") +
                    common::to_string(detected));
    return true;
}

}  // namespace ltm::localisation
