#include "odometry/core/odometry_config.hpp"

#include <gtest/gtest.h>

namespace ltm::odometry {
namespace {

TEST(OdometryConfig, DefaultsAndPresetsAreValid) {
    EXPECT_EQ(validate(OdometryConfig{}), "");
    for (const std::string& name : common::sensor_preset_names()) {
        EXPECT_EQ(validate(preset_config(common::parse_sensor_preset(name))), "") << name;
    }
    EXPECT_LT(preset_config(SensorPreset::kNarrow).preprocess.max_range,
              preset_config(SensorPreset::kHdl64).preprocess.max_range);
    EXPECT_THROW(common::parse_sensor_preset("hdl32"), std::invalid_argument);
}

TEST(OdometryConfig, ValidationNamesTheKey) {
    OdometryConfig c;
    c.preprocess.max_range = 1.0;
    c.preprocess.min_range = 2.0;
    EXPECT_NE(validate(c).find("odometry.preprocess.max_range"), std::string::npos) << validate(c);
    c = OdometryConfig{};
    c.local_map.switch_distance = 80.0;
    EXPECT_NE(validate(c).find("odometry.local_map.switch_distance"), std::string::npos);
    c = OdometryConfig{};
    c.prediction = "linear";
    EXPECT_NE(validate(c).find("odometry.prediction"), std::string::npos);
    c = OdometryConfig{};
    c.coarse_voxel_factor = 1;
    EXPECT_NE(validate(c).find("odometry.coarse_voxel_factor"), std::string::npos);
    c = OdometryConfig{};
    c.voxel.min_planarity = 1.5;
    EXPECT_NE(validate(c).find("odometry.voxel.min_planarity"), std::string::npos);
    c = OdometryConfig{};
    c.threads = 0;
    EXPECT_NE(validate(c).find("odometry.threads"), std::string::npos);
}

}  // namespace
}  // namespace ltm::odometry
