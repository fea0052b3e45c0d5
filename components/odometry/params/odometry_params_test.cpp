#include "odometry/params/odometry_params.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace ltm::odometry {
namespace {

runtime::Parameters params_of(const std::string& yaml) {
    return runtime::Parameters(YAML::Load(yaml), "test.yaml", "odometry");
}

std::string error_of(const std::string& yaml) {
    try {
        runtime::Parameters p = params_of(yaml);
        load_odometry_config(p);
        p.check_all_used();
    } catch (const runtime::ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(OdometryParams, PresetThenOverrides) {
    runtime::Parameters p = params_of(
        "preset: narrow\nvoxel_size: 0.4\npreprocess: {max_range: 30}\n"
        "registration: {stability_weighting: false}\nprediction: frame\n");
    const OdometryConfig c = load_odometry_config(p);
    EXPECT_NO_THROW(p.check_all_used());
    const OdometryConfig narrow = preset_config(SensorPreset::kNarrow);
    EXPECT_DOUBLE_EQ(c.voxel_size, 0.4);
    EXPECT_DOUBLE_EQ(c.preprocess.max_range, 30.0);
    EXPECT_FALSE(c.registration.stability_weighting);
    EXPECT_EQ(c.prediction, "frame");
    EXPECT_EQ(c.coarse_voxel_factor, narrow.coarse_voxel_factor);  // untouched keys: the preset's
    EXPECT_DOUBLE_EQ(c.preprocess.min_range, narrow.preprocess.min_range);
    // Nothing given: the default preset.
    runtime::Parameters empty(YAML::Node(), "test.yaml", "odometry");
    EXPECT_DOUBLE_EQ(load_odometry_config(empty).voxel_size,
                     preset_config(SensorPreset::kHdl64).voxel_size);
}

TEST(OdometryParams, RejectsWhatItDoesNotKnowNamingFileLineAndKey) {
    EXPECT_EQ(error_of("voxel_size: 1\npreprocess: {max_rnage: 30}")
                  .rfind("test.yaml:2: odometry.preprocess.max_rnage: unknown parameter", 0),
              0u);
    EXPECT_EQ(error_of("voxel_size: big"),
              "test.yaml:1: odometry.voxel_size: expected a number, got 'big'");
    EXPECT_NE(
        error_of("a: 1\nvoxel_size: -1").find("test.yaml:2: odometry.voxel_size: must be > 0"),
        std::string::npos)
        << error_of("a: 1\nvoxel_size: -1");
    EXPECT_NE(error_of("preset: hdl32")
                  .find("test.yaml:1: odometry.preset: unknown sensor preset 'hdl32'"),
              std::string::npos);
    EXPECT_NE(error_of("registration: {kernel_scale: [1]}")
                  .find("odometry.registration.kernel_scale: expected a number"),
              std::string::npos);
}

TEST(OdometryParams, RulesOfFieldsAndAcrossFieldsPointAtTheKeysLine) {
    EXPECT_EQ(error_of("prediction: linear"),
              "test.yaml:1: odometry.prediction: must be time, frame or none (got 'linear')");
    EXPECT_EQ(error_of("threads: 2\nregistration:\n  min_correspondences: 3"),
              "test.yaml:3: odometry.registration.min_correspondences: must be >= 6 (got 3)");
    EXPECT_EQ(error_of("preprocess:\n  min_range: 5\n  max_range: 4"),
              "test.yaml:3: odometry.preprocess.max_range: must exceed min_range");
    EXPECT_EQ(error_of("local_map:\n  half_extent: 30\n  switch_distance: 40"),
              "test.yaml:3: odometry.local_map.switch_distance: must be smaller than "
              "local_map.half_extent");
    // A key the file does not give: the line of the parameters' map.
    EXPECT_EQ(error_of("voxel_size: 0.5\nlocal_map: {half_extent: 10}"),
              "test.yaml:2: odometry.local_map.switch_distance: must be smaller than "
              "local_map.half_extent");
}

TEST(OdometryParams, UnderAPrefixAsInALaunchConfig) {
    runtime::Parameters p =
        params_of("frame_id: odom\nodometry: {preset: vlp16, keyframe: {distance: 3.0}}\n");
    const OdometryConfig c = load_odometry_config(p, "odometry");
    p.get<std::string>("frame_id", "");
    EXPECT_NO_THROW(p.check_all_used());
    EXPECT_DOUBLE_EQ(c.keyframe.distance, 3.0);
    EXPECT_DOUBLE_EQ(c.voxel_size, preset_config(SensorPreset::kVlp16).voxel_size);
}

// `preset: auto` (the odometry component's default): no preset yet, the keys applied to the one
// the scans tell; a tool that wants a config now refuses it, naming the key.
TEST(OdometryParams, AutoIsDecidedLaterAndItsKeysApplyToThePresetTold) {
    runtime::Parameters p = params_of("preset: auto\nvoxel_size: 0.45\n");
    EXPECT_FALSE(load_odometry_preset(p, "", "hdl64").has_value());
    runtime::Parameters q(YAML::Node(), "test.yaml", "odometry");
    EXPECT_FALSE(load_odometry_preset(q, "", "auto").has_value());  // the component's default
    const OdometryConfig c = load_odometry_config_for(p, "", SensorPreset::kVlp16);
    EXPECT_DOUBLE_EQ(c.voxel_size, 0.45);
    EXPECT_DOUBLE_EQ(c.preprocess.max_range,
                     preset_config(SensorPreset::kVlp16).preprocess.max_range);
    EXPECT_NE(error_of("preset: auto\n").find("odometry.preset"), std::string::npos);
    EXPECT_NE(error_of("preset: vlp64\n").find("or auto"), std::string::npos);
}

}  // namespace
}  // namespace ltm::odometry
