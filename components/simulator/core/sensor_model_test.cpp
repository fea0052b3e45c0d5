#include "simulator/core/sensor_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "simulator/core/materials.hpp"

namespace ltm::sim {
namespace {

double elevation_deg(const Eigen::Vector3f& d) {
    return std::atan2(d.z(), d.head<2>().norm()) * 180.0 / M_PI;
}

TEST(SensorModel, Hdl64eBeamLayoutLikeKitti) {
    SensorConfig c;
    ASSERT_TRUE(make_sensor_preset("hdl64e", c));
    const SensorModel m(c);
    ASSERT_EQ(m.rings(), 64);
    std::vector<Pulse> scratch;
    const auto& pulses = m.pulses(0, scratch);
    ASSERT_EQ(pulses.size(), 64u * 2083u);
    std::map<int, int> per_ring;
    std::map<int, double> ring_elevation;
    for (const auto& p : pulses) {
        ++per_ring[p.ring];
        ring_elevation[p.ring] = elevation_deg(p.dir);
        EXPECT_GE(p.time, 0.0f);
        EXPECT_LT(p.time, 0.1f);
    }
    for (const auto& [ring, n] : per_ring) EXPECT_EQ(n, 2083) << "ring " << ring;
    EXPECT_NEAR(ring_elevation[0], 2.0, 1e-4);
    EXPECT_NEAR(ring_elevation[63], -24.8, 1e-4);
    EXPECT_NEAR(ring_elevation[1] - ring_elevation[0], -1.0 / 3.0, 1e-4);  // upper block
    EXPECT_NEAR(ring_elevation[40] - ring_elevation[39], -0.515, 1e-3);    // lower block
    for (int r = 1; r < 64; ++r) EXPECT_LT(ring_elevation[r], ring_elevation[r - 1]);  // top first
    // KITTI order: each ring starts forward and turns counter-clockwise; time 0 is at the rear.
    EXPECT_NEAR(pulses[0].azimuth, 0.0, 1e-6);
    EXPECT_GT(pulses[10].azimuth, pulses[9].azimuth);
    EXPECT_NEAR(pulses[0].time, 0.05, 1e-4);
    EXPECT_NEAR(pulses[2083 / 2].time, 0.0, 1e-4);
}

TEST(SensorModel, VelodynePuckLayouts) {
    SensorConfig c;
    ASSERT_TRUE(make_sensor_preset("vlp32c", c));
    ASSERT_EQ(c.elevations_deg.size(), 32u);
    EXPECT_DOUBLE_EQ(c.elevations_deg.front(), 15.0);
    EXPECT_DOUBLE_EQ(c.elevations_deg.back(), -25.0);
    std::vector<Pulse> scratch;
    EXPECT_EQ(SensorModel(c).pulses(0, scratch).size(), 32u * 1800u);
    ASSERT_TRUE(make_sensor_preset("vlp16", c));
    ASSERT_EQ(c.elevations_deg.size(), 16u);
    for (std::size_t i = 0; i < 16; ++i) EXPECT_DOUBLE_EQ(c.elevations_deg[i], 15.0 - 2.0 * i);
    EXPECT_FALSE(make_sensor_preset("hdl32", c));
}

TEST(SensorModel, Os164UniformBeamsAndColumns) {
    SensorConfig c;
    ASSERT_TRUE(make_sensor_preset("os1_64", c));
    EXPECT_EQ(c.model, "os1_64");
    EXPECT_DOUBLE_EQ(c.min_range, 0.3);
    EXPECT_DOUBLE_EQ(c.max_range, 120.0);
    const SensorModel m(c);
    ASSERT_EQ(m.rings(), 64);
    std::vector<Pulse> scratch;
    const auto& pulses = m.pulses(0, scratch);
    ASSERT_EQ(pulses.size(), 64u * 1024u);
    std::map<int, int> per_ring;
    std::map<int, double> ring_elevation;
    for (const auto& p : pulses) {
        ++per_ring[p.ring];
        ring_elevation[p.ring] = elevation_deg(p.dir);
        EXPECT_GE(p.time, 0.0f);
        EXPECT_LT(p.time, 0.1f);
    }
    ASSERT_EQ(per_ring.size(), 64u);
    for (const auto& [ring, n] : per_ring) EXPECT_EQ(n, 1024) << "ring " << ring;
    EXPECT_NEAR(ring_elevation[0], 22.5, 1e-4);
    EXPECT_NEAR(ring_elevation[63], -22.5, 1e-4);
    for (int r = 1; r < 64; ++r)  // uniform spacing, top first
        EXPECT_NEAR(ring_elevation[r] - ring_elevation[r - 1], -45.0 / 63.0, 1e-4) << r;
    // Swapping it in keeps the mount and timing of the scenario's sensor.
    SensorConfig mounted;
    ASSERT_TRUE(make_sensor_preset("livox_avia", mounted));
    mounted.height = 0.7;
    mounted.motion_distortion = true;
    ASSERT_TRUE(replace_sensor("os1_64", mounted));
    EXPECT_EQ(mounted.elevations_deg.size(), 64u);
    EXPECT_EQ(mounted.pattern, ScanPattern::kSpinning);
    EXPECT_DOUBLE_EQ(mounted.height, 0.7);
    EXPECT_TRUE(mounted.motion_distortion);
    EXPECT_NE(sensor_preset_names().find("os1_64"), std::string::npos);
}

TEST(SensorModel, RosetteStaysInItsFieldAndNeverRepeats) {
    SensorConfig c;
    ASSERT_TRUE(make_sensor_preset("solid_state", c));
    EXPECT_EQ(c.model, "livox_avia");
    const SensorModel m(c);
    std::vector<Pulse> a, b;
    const auto& s0 = m.pulses(0, a);
    ASSERT_EQ(s0.size(), 20000u);
    double max_angle = 0;
    for (const auto& p : s0) {
        max_angle =
            std::max(max_angle, std::acos(std::clamp<double>(p.dir.x(), -1, 1)) * 180 / M_PI);
        EXPECT_NEAR(p.dir.norm(), 1.0, 1e-5);
    }
    EXPECT_LT(max_angle, 0.5 * c.fov_deg + 3.0);  // plus the laser offsets
    EXPECT_GT(max_angle, 0.5 * c.fov_deg - 3.0);
    const auto& s1 = m.pulses(1, b);
    int same = 0;
    for (std::size_t k = 0; k < s0.size(); ++k) same += (s0[k].dir - s1[k].dir).norm() < 1e-4f;
    EXPECT_LT(same, 50);
}

TEST(SensorModel, ReturnsFadeWithRangeIncidenceAndDarkness) {
    SensorConfig c;
    ASSERT_TRUE(make_sensor_preset("hdl64e", c));
    const SensorModel m(c);
    EXPECT_NEAR(m.return_power(0.1, 1.0, c.range_at_10pct), 1.0, 1e-12);
    EXPECT_NEAR(SensorModel::detection_probability(m.return_power(0.5, 1.0, 10.0)), 1.0, 1e-12);
    EXPECT_NEAR(SensorModel::detection_probability(m.return_power(0.1, 1.0, 200.0)), 0.0, 1e-12);
    double prev = 1e9;
    for (double r = 10; r < 200; r += 5) {
        const double q = m.return_power(0.3, 0.5, r);
        EXPECT_LT(q, prev);
        prev = q;
    }
    EXPECT_LT(m.return_power(0.3, 0.05, 70.0), m.return_power(0.3, 1.0, 70.0));
    EXPECT_LT(m.return_power(0.05, 1.0, 60.0), m.return_power(0.6, 1.0, 60.0));
    // Intensity: the reflectivity when strong, fading to 0 at the threshold.
    EXPECT_NEAR(SensorModel::intensity(0.3, m.return_power(0.3, 0.8, 5.0)), 0.3, 1e-12);
    EXPECT_EQ(SensorModel::intensity(0.3, 1.0), 0.0);
    EXPECT_LT(SensorModel::intensity(0.3, m.return_power(0.3, 0.1, 40.0)), 0.2);
    for (int k = 0; k < static_cast<int>(Material::kCount); ++k) {  // every material is described
        ASSERT_NE(material_properties(static_cast<Material>(k)).name, nullptr);
        EXPECT_GT(material_properties(static_cast<Material>(k)).reflectivity, 0.0f);
    }
}

TEST(SensorModel, EgoBoxBlocksPulsesIntoTheVehicle) {
    SensorConfig c;
    ASSERT_TRUE(make_sensor_preset("hdl64e", c));
    c.has_ego_box = true;
    c.ego_box =
        Eigen::AlignedBox3d(Eigen::Vector3d(-2.1, -0.8, -2.0), Eigen::Vector3d(1.9, 0.8, -0.7));
    const SensorModel m(c);
    std::vector<Pulse> scratch;
    int blocked = 0, blocked_up = 0;
    for (const auto& p : m.pulses(0, scratch)) {
        blocked += p.blocked;
        blocked_up += p.blocked && p.dir.z() > -0.3f;
    }
    EXPECT_GT(blocked, 1000);
    EXPECT_EQ(blocked_up, 0);  // only steep pulses reach the car body
}

}  // namespace
}  // namespace ltm::sim
