// The sensor preset table: every preset has a row, every row every value, in range.
#include "common/core/sensor_preset.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>

namespace ltm::common {
namespace {

TEST(SensorPresetTable, EveryPresetHasEveryValue) {
    std::set<std::string> names, models;
    for (SensorPreset p : kSensorPresets) {
        const SensorPresetRow& r = sensor_preset_row(p);
        SCOPED_TRACE(r.name);
        ASSERT_NE(r.name, nullptr);
        EXPECT_TRUE(names.insert(r.name).second) << "two presets named " << r.name;
        EXPECT_EQ(parse_sensor_preset(r.name), p);
        EXPECT_STREQ(to_string(p), r.name);
        ASSERT_NE(r.sensor, nullptr);
        EXPECT_GT(std::string(r.sensor).size(), 0u);
        ASSERT_NE(r.simulator_model, nullptr);
        EXPECT_TRUE(models.insert(r.simulator_model).second);
        // The sensor and its mount.
        EXPECT_GE(r.rings, 0);
        EXPECT_GT(r.vertical_fov_deg, 0.0);
        EXPECT_LE(r.vertical_fov_deg, 180.0);
        EXPECT_GT(r.horizontal_fov_deg, 0.0);
        EXPECT_LE(r.horizontal_fov_deg, 360.0);
        EXPECT_GT(r.descriptor_height, 0.2);
        EXPECT_LT(r.descriptor_height, 5.0);
        // The odometry.
        const auto& o = r.odometry;
        EXPECT_GT(o.voxel_size, 0.0);
        EXPECT_GE(o.coarse_voxel_factor, 1);
        EXPECT_GE(o.min_range, 0.0);
        EXPECT_GT(o.max_range, o.min_range);
        EXPECT_GT(o.map_sample_fraction, 0.0);
        EXPECT_GT(o.registration_sample_fraction, 0.0);
        EXPECT_GT(o.local_map_half_extent, o.local_map_switch_distance);
        EXPECT_GT(o.local_map_switch_distance, 0.0);
        EXPECT_GT(o.keyframe_distance, 0.0);
        EXPECT_GT(o.min_scan_points, 0);
        // Places.
        const auto& pl = r.places;
        EXPECT_GT(pl.descriptor_max_range, 0.0);
        EXPECT_GE(pl.loop_exclude_recent_s, 0.0);
        EXPECT_GE(pl.loop_exclude_recent_keyframes, 0);
        EXPECT_GT(pl.loop_max_distance, 0.0);
        EXPECT_GE(pl.loop_cooldown_keyframes, 0);
        EXPECT_GE(pl.verify_downsample, 0.0);
        EXPECT_GE(pl.verify_min_inliers, 1);
        EXPECT_GE(pl.verify_coarse_factor, 2);
        EXPECT_GT(pl.loop_max_correction_translation, 0.0);
        // The localisation.
        EXPECT_GT(r.localisation.off_map_margin, 0.0);
        EXPECT_GT(r.localisation.feature_max_range, 0.0);
    }
    EXPECT_EQ(names.size(), sensor_preset_names().size());
}

TEST(SensorPresetTable, UnknownNamesAreRefusedWithTheKnownOnes) {
    try {
        parse_sensor_preset("hdl32");
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("hdl64, vlp32, vlp16, narrow, os1-64"),
                  std::string::npos)
            << e.what();
    }
}

// `preset: auto` gives components that see no scans the spinning sensors' place, loop and
// localisation settings (common/core/sensor_detect.hpp, kAutoSpinningPreset): every spinning
// preset must have the same ones, or auto would be a guess between them.
TEST(SensorPresetTable, SpinningPresetsShareWhatAutoGivesComponentsWithoutScans) {
    const SensorPresetRow& a = sensor_preset_row(SensorPreset::kHdl64);
    for (SensorPreset p : kSensorPresets) {
        const SensorPresetRow& r = sensor_preset_row(p);
        if (r.horizontal_fov_deg < 360.0) continue;
        SCOPED_TRACE(r.name);
        EXPECT_EQ(r.descriptor_height, a.descriptor_height);
        EXPECT_EQ(r.places.descriptor_max_range, a.places.descriptor_max_range);
        EXPECT_EQ(r.places.loop_exclude_recent_s, a.places.loop_exclude_recent_s);
        EXPECT_EQ(r.places.loop_exclude_recent_keyframes, a.places.loop_exclude_recent_keyframes);
        EXPECT_EQ(r.places.loop_max_distance, a.places.loop_max_distance);
        EXPECT_EQ(r.places.loop_cooldown_keyframes, a.places.loop_cooldown_keyframes);
        EXPECT_EQ(r.places.verify_downsample, a.places.verify_downsample);
        EXPECT_EQ(r.places.verify_min_inliers, a.places.verify_min_inliers);
        EXPECT_EQ(r.places.verify_coarse_factor, a.places.verify_coarse_factor);
        EXPECT_EQ(r.places.loop_max_correction_translation,
                  a.places.loop_max_correction_translation);
        EXPECT_EQ(r.localisation.off_map_margin, a.localisation.off_map_margin);
        EXPECT_EQ(r.localisation.feature_max_range, a.localisation.feature_max_range);
    }
}

}  // namespace
}  // namespace ltm::common
