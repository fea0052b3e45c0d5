// Every odometry preset on the simulated sensor of its kind (issue 11, "presets that fit real
// sensors"): the simulator's fast_turns site seen by an HDL-64E, a VLP-32C, a VLP-16, a Livox Avia
// and an Ouster OS1-64, the scans raw (motion distortion on, per-point time written) so that the
// odometry de-skews them with the sensor's own per-point time. The first 40 scans of fast_turns
// (4 s at 3 m/s) are all registered and their motion agrees with the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "odometry/core/odometry.hpp"
#include "simulator/core/scenario_yaml.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::odometry {
namespace {

struct Case {
    const char* sensor;  // simulator preset
    SensorPreset preset;
};

class SensorPresets : public testing::TestWithParam<Case> {};

TEST_P(SensorPresets, TracksTheSimulatedSensorWithPerPointTime) {
    sim::ScenarioConfig sc =
        sim::load_scenario(LTM_SOURCE_DIR "/components/simulator/scenarios/fast_turns.yaml");
    ASSERT_TRUE(sim::replace_sensor(GetParam().sensor, sc.sensor));
    sc.sensor.motion_distortion = true;
    sc.sensor.per_point_time = true;
    const sim::Simulator sim(sc, 0);
    Odometry odo(preset_config(GetParam().preset));
    std::vector<Eigen::Isometry3d> est, truth;
    std::size_t deskewed = 0;
    const std::size_t n = std::min<std::size_t>(40, sim.num_scans());
    for (std::size_t i = 0; i < n; ++i) {
        sim::SimScan s;
        sim.scan(i, s);
        ASSERT_TRUE(s.cloud.has_time());
        const FrameResult r = odo.register_frame(s.cloud);
        // Registered, or (a narrow view at the start: a direction its registration cannot
        // observe) degenerate with the motion model's position along it; never lost.
        ASSERT_TRUE(r.registered() || r.status == FrameStatus::kDegenerate || i == 0)
            << "scan " << i << ": " << r.message;
        deskewed += r.deskewed;
        est.push_back(r.T_odom_lidar);
        truth.push_back(s.T_world_lidar);
    }
    EXPECT_GE(deskewed, n - 1);  // from the second scan on
    // The motion over the last 2 s (6 m) against the truth. (The first scans start at full speed
    // with no motion known: the first map is not de-skewed, see components/odometry/README.md.)
    const Eigen::Isometry3d e = est[n / 2].inverse() * est.back();
    const Eigen::Isometry3d t = truth[n / 2].inverse() * truth.back();
    const Eigen::Isometry3d d = t.inverse() * e;
    EXPECT_GT(t.translation().norm(), 3.0);
    // Loose (a test, not a benchmark: `./ltm bench hard_cases --sim` measures accuracy; these 2 s
    // of this start measure 0.03-0.3 m / 0.3-1.9 deg): a preset that does not fit its sensor
    // ends metres off or loses track.
    EXPECT_LT(d.translation().norm(), 0.5);
    EXPECT_LT(Eigen::AngleAxisd(d.linear()).angle() * 180.0 / M_PI, 3.0);
}

INSTANTIATE_TEST_SUITE_P(Each, SensorPresets,
                         testing::Values(Case{"hdl64e", SensorPreset::kHdl64},
                                         Case{"vlp32c", SensorPreset::kVlp32},
                                         Case{"vlp16", SensorPreset::kVlp16},
                                         Case{"livox_avia", SensorPreset::kNarrow},
                                         Case{"os1_64", SensorPreset::kOs1_64}),
                         [](const testing::TestParamInfo<Case>& info) {
                             return std::string(to_string(info.param.preset)) == "os1-64"
                                        ? std::string("os1_64")
                                        : std::string(to_string(info.param.preset));
                         });

}  // namespace
}  // namespace ltm::odometry
