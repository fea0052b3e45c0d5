// The sensor class from the scans (common/core/sensor_detect.hpp) on every simulated sensor: a
// scan of each in a small yard is told as its preset (the preset table's simulator model), with
// the ring field and without it (the elevations).
#include <gtest/gtest.h>

#include "common/core/sensor_detect.hpp"
#include "simulator/core/simulator.hpp"

namespace ltm::sim {
namespace {

// A small yard, a 20 m straight route (simulator_test.cpp's world, without the walker).
ScenarioConfig yard(const std::string& model) {
    ScenarioConfig sc;
    sc.name = "yard";
    sc.seed = 3;
    EXPECT_TRUE(make_sensor_preset(model, sc.sensor)) << model;
    sc.world.margin = 25;
    sc.world.terrain.amplitude = 0.5;
    sc.world.terrain.wavelength = 60;
    sc.world.substation.yard = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(30, 20));
    sc.world.substation.bay_width = 10;
    SessionConfig s;
    s.route.waypoints = {{2, 10, 0}, {28, 10, 0}};
    s.route.speed = 4.0;
    sc.sessions.push_back(s);
    return sc;
}

TEST(SensorDetectSim, EverySimulatedSensorIsToldAsItsPreset) {
    for (const common::SensorPreset p : common::kSensorPresets) {
        const common::SensorPresetRow& row = common::sensor_preset_row(p);
        SCOPED_TRACE(row.simulator_model);
        const Simulator sim(yard(row.simulator_model));
        SimScan scan;
        ASSERT_TRUE(sim.scan(3, scan));
        const common::SensorGuess by_elevation =
            common::classify_scan(common::measure_scan(scan.cloud));
        EXPECT_EQ(by_elevation.preset, p) << by_elevation.reason;
        const common::ScanShape with_field = common::measure_scan(scan.cloud, &scan.rings);
        EXPECT_TRUE(with_field.rings_from_field);
        const common::SensorGuess by_field = common::classify_scan(with_field);
        EXPECT_EQ(by_field.preset, p) << by_field.reason;
        common::SensorDetector detector;
        EXPECT_TRUE(detector.add(scan.cloud));
        EXPECT_TRUE(detector.detected());
        EXPECT_EQ(detector.preset(), p) << detector.line();
    }
}

}  // namespace
}  // namespace ltm::sim
