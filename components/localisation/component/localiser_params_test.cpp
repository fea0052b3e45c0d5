#include "localisation/component/localiser_params.hpp"

#include <gtest/gtest.h>

namespace ltm::localisation {
namespace {

runtime::Parameters params_of(const std::string& yaml) {
    return runtime::Parameters(YAML::Load(yaml), "test.yaml", "localisation");
}

std::string error_of(const std::string& yaml) {
    try {
        runtime::Parameters p = params_of(yaml);
        load_localiser_config(p, load_sensor_preset(p));
        p.check_all_used();
    } catch (const runtime::ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(LocaliserParams, PresetThenOverrides) {
    runtime::Parameters p = params_of(
        "preset: narrow\nlost_after: 2.5\nglobal: {candidates: 7, yaw_offsets: [0, 180]}\n"
        "tracking: {max_iterations: 12}\n");
    const LocaliserConfig c = load_localiser_config(p, load_sensor_preset(p));
    EXPECT_NO_THROW(p.check_all_used());
    const LocaliserConfig narrow = localiser_preset(common::SensorPreset::kNarrow);
    EXPECT_DOUBLE_EQ(c.lost_after, 2.5);
    EXPECT_EQ(c.global.candidates, 7);
    EXPECT_EQ(c.global.yaw_offsets, (std::vector<double>{0.0, 180.0}));
    EXPECT_EQ(c.tracking.max_iterations, 12);
    // Untouched keys: the preset's.
    EXPECT_EQ(c.global.verification.min_inliers, narrow.global.verification.min_inliers);
    EXPECT_DOUBLE_EQ(c.max_gap, narrow.max_gap);
}

TEST(LocaliserParams, RejectsWhatItDoesNotKnowNamingFileLineAndKey) {
    EXPECT_EQ(error_of("lost_after: 1\nglobal: {candiates: 3}")
                  .rfind("test.yaml:2: localisation.global.candiates: unknown parameter", 0),
              0u)
        << error_of("lost_after: 1\nglobal: {candiates: 3}");
    EXPECT_EQ(error_of("lost_after: soon"),
              "test.yaml:1: localisation.lost_after: expected a number, got 'soon'");
    EXPECT_NE(error_of("a: 1\nmax_gap: -1").find("test.yaml:2: localisation.max_gap: must be > 0"),
              std::string::npos)
        << error_of("a: 1\nmax_gap: -1");
    EXPECT_NE(error_of("preset: hdl32")
                  .find("test.yaml:1: localisation.preset: unknown sensor preset 'hdl32'"),
              std::string::npos)
        << error_of("preset: hdl32");
}

TEST(LocaliserParams, AutoIsTheDefaultAndANameWins) {
    runtime::Parameters none(YAML::Node(), "test.yaml", "localisation");
    EXPECT_FALSE(load_sensor_preset_or_auto(none, "auto").has_value());
    runtime::Parameters named = params_of("preset: os1-64\n");
    EXPECT_EQ(load_sensor_preset_or_auto(named, "auto"), common::SensorPreset::kOs1_64);
    runtime::Parameters wrong = params_of("preset: velodyne\n");
    EXPECT_THROW(load_sensor_preset_or_auto(wrong, "auto"), runtime::ConfigError);
}

}  // namespace
}  // namespace ltm::localisation
