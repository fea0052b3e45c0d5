#include "odometry/core/odometry_config.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace ltm::odometry {
namespace {

// "key: problem" of the first problem, "" when valid.
std::string problem_of(const OdometryConfig& c) {
    const auto p = validate(c);
    return p ? p->key + ": " + p->problem : "";
}

TEST(OdometryConfig, DefaultsAndPresetsAreValid) {
    EXPECT_EQ(problem_of(OdometryConfig{}), "");
    for (const std::string& name : common::sensor_preset_names()) {
        EXPECT_EQ(problem_of(preset_config(common::parse_sensor_preset(name))), "") << name;
    }
    EXPECT_LT(preset_config(SensorPreset::kNarrow).preprocess.max_range,
              preset_config(SensorPreset::kHdl64).preprocess.max_range);
    EXPECT_THROW(common::parse_sensor_preset("hdl32"), std::invalid_argument);
}

TEST(OdometryConfig, EachFieldRuleNamesTheKey) {
    auto with = [](auto change) {
        OdometryConfig c;
        change(c);
        return problem_of(c);
    };
    EXPECT_EQ(with([](OdometryConfig& c) { c.voxel_size = -1; }),
              "voxel_size: must be > 0 (got -1)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.voxel_size = std::nan(""); }),
              "voxel_size: must be > 0 (got nan)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.prediction = "linear"; }),
              "prediction: must be time, frame or none (got 'linear')");
    EXPECT_EQ(with([](OdometryConfig& c) { c.coarse_voxel_factor = 1; }),
              "coarse_voxel_factor: must be 0 or in [2, 16] (got 1)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.coarse_voxel_factor = 0; }), "");
    EXPECT_EQ(with([](OdometryConfig& c) { c.threads = 0; }), "threads: must be >= 1 (got 0)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.preprocess.min_range = -1; }),
              "preprocess.min_range: must be >= 0 (got -1)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.voxel.min_planarity = 1.5; }),
              "voxel.min_planarity: must be in [0, 1] (got 1.5)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.voxel.min_points_for_normal = 2; }),
              "voxel.min_points_for_normal: must be >= 3 (got 2)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.registration.min_correspondences = 5; }),
              "registration.min_correspondences: must be >= 6 (got 5)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.registration.kernel_scale = INFINITY; }),
              "registration.kernel_scale: must be > 0 (got inf)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.tracking.retry_residual_ratio = 0.5; }),
              "tracking.retry_residual_ratio: must be >= 1 (got 0.5)");
    EXPECT_EQ(with([](OdometryConfig& c) { c.keyframe.angle = -1; }),
              "keyframe.angle: must be >= 0 (got -1)");
}

TEST(OdometryConfig, RulesAcrossFields) {
    OdometryConfig c;
    c.preprocess.max_range = 1.0;
    c.preprocess.min_range = 2.0;
    EXPECT_EQ(problem_of(c), "preprocess.max_range: must exceed min_range");
    c = OdometryConfig{};
    c.local_map.switch_distance = 80.0;
    EXPECT_EQ(problem_of(c),
              "local_map.switch_distance: must be smaller than local_map.half_extent");
    c = OdometryConfig{};
    c.voxel.max_points = 4;
    EXPECT_EQ(problem_of(c), "voxel.max_points: must be >= min_points_for_normal (5)");
    c = OdometryConfig{};
    c.voxel_size = 1e-5;
    c.local_map.half_extent = 10.0;
    c.local_map.switch_distance = 5.0;
    EXPECT_NE(problem_of(c).find("local_map.half_extent: "), std::string::npos) << problem_of(c);
}

TEST(OdometryConfig, EveryFieldHasOneKeyAndARule) {
    OdometryConfig c;
    std::set<std::string> keys;
    int fields = 0;
    visit_fields(c, [&](const std::string& key, auto& /*field*/, const auto& /*rule*/) {
        EXPECT_TRUE(keys.insert(key).second) << "key visited twice: " << key;
        ++fields;
    });
    EXPECT_EQ(fields, 79);  // 59 (tracking.restart_gap_cadence, restart_kept_out,
                            // heading_hold_ratio, spin_rate, spin_window) + 20 observability.*
}

}  // namespace
}  // namespace ltm::odometry
