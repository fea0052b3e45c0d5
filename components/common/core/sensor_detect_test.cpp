// The sensor class from the scans: bad input refused (not guessed), the real KITTI HDL-64E and
// Livox Avia scans when /work/shared is there (skipped otherwise), ring fields, the detector's
// fallback. The simulated sensors: simulator/core/sensor_detect_sim_test.cpp.
#include "common/core/sensor_detect.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <random>

#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"

namespace ltm::common {
namespace {

const std::string kShared = LTM_SOURCE_DIR "/../shared/data";

// A ring of `columns` points at elevation `e` [deg], 20 m away.
void add_ring(PointCloud& c, double e, int columns, double around_deg = 360.0) {
    const double k = M_PI / 180.0;
    for (int i = 0; i < columns; ++i) {
        const double a = (-around_deg / 2 + around_deg * i / columns) * k;
        c.points.emplace_back(float(20 * std::cos(e * k) * std::cos(a)),
                              float(20 * std::cos(e * k) * std::sin(a)),
                              float(20 * std::sin(e * k)));
    }
}

TEST(SensorDetect, EmptyAndNonFiniteScansAreRefusedNotGuessed) {
    PointCloud empty;
    const SensorGuess g = classify_scan(measure_scan(empty));
    EXPECT_FALSE(g.preset);
    EXPECT_NE(g.reason.find("too few points"), std::string::npos) << g.reason;

    PointCloud nan;
    const float q = std::numeric_limits<float>::quiet_NaN();
    for (int i = 0; i < 50000; ++i) nan.points.emplace_back(q, 1.0f, std::nanf(""));
    const ScanShape s = measure_scan(nan);
    EXPECT_EQ(s.points, 0u);
    EXPECT_EQ(s.non_finite, 50000u);
    EXPECT_FALSE(classify_scan(s).preset);

    // NaN points among a VLP-16's rings are ignored.
    PointCloud vlp16;
    for (int r = 0; r < 16; ++r) add_ring(vlp16, 15.0 - 2.0 * r, 1800);
    for (int i = 0; i < 1000; ++i) vlp16.points.emplace_back(q, q, q);
    const ScanShape v = measure_scan(vlp16);
    EXPECT_EQ(v.rings, 16);
    EXPECT_EQ(v.non_finite, 1000u);
    EXPECT_EQ(classify_scan(v).preset, SensorPreset::kVlp16) << classify_scan(v).reason;
}

TEST(SensorDetect, RingCountsNoPresetHasAndHalfViewsAreRefused) {
    PointCloud eight;  // 8 beams: no such preset
    for (int r = 0; r < 8; ++r) add_ring(eight, 10.0 - 3.0 * r, 1800);
    EXPECT_FALSE(classify_scan(measure_scan(eight)).preset);
    PointCloud half;  // 32 rings over 220 deg: neither spinning nor narrow
    for (int r = 0; r < 32; ++r) add_ring(half, 15.0 - 1.25 * r, 1200, 220.0);
    const SensorGuess g = classify_scan(measure_scan(half));
    EXPECT_FALSE(g.preset) << g.reason;
}

TEST(SensorDetect, TheRingFieldCountsWhenGiven) {
    PointCloud c;
    for (int r = 0; r < 4; ++r) add_ring(c, -5.0 + r, 2000);  // 4 elevations ...
    std::vector<std::uint16_t> rings;
    for (std::size_t i = 0; i < c.size(); ++i) rings.push_back(std::uint16_t(i % 32));  // 32 beams
    const ScanShape s = measure_scan(c, &rings);
    EXPECT_TRUE(s.rings_from_field);
    EXPECT_EQ(s.rings, 32);
    EXPECT_EQ(classify_scan(s).preset, SensorPreset::kVlp32);
    rings.pop_back();  // not one per point: the elevations count
    EXPECT_EQ(measure_scan(c, &rings).rings, 4);
}

TEST(SensorDetect, TheDetectorFallsBackAfterItsScansAndSaysSo) {
    SensorDetector d(SensorDetectConfig{3, SensorPreset::kHdl64});
    PointCloud empty;
    EXPECT_FALSE(d.add(empty));
    EXPECT_FALSE(d.add(empty));
    EXPECT_TRUE(d.add(empty));
    EXPECT_FALSE(d.detected());
    EXPECT_EQ(d.preset(), SensorPreset::kHdl64);
    EXPECT_EQ(d.line().rfind("unknown sensor (", 0), 0u) << d.line();
    EXPECT_NE(d.line().find("using hdl64"), std::string::npos) << d.line();

    SensorDetector e;  // an empty first scan, then a VLP-16's
    EXPECT_FALSE(e.add(empty));
    PointCloud vlp16;
    for (int r = 0; r < 16; ++r) add_ring(vlp16, 15.0 - 2.0 * r, 1800);
    EXPECT_TRUE(e.add(vlp16));
    EXPECT_TRUE(e.detected());
    EXPECT_EQ(e.preset(), SensorPreset::kVlp16);
    EXPECT_EQ(e.line().rfind("sensor preset vlp16", 0), 0u) << e.line();
}

TEST(SensorDetect, RealKittiHdl64eScansAreHdl64) {
    const std::string dir = kShared + "/kitti/sequences/00/velodyne";
    if (!std::filesystem::exists(dir + "/000000.bin"))
        GTEST_SKIP() << "KITTI 00 not found under ../shared/data/kitti";
    for (const char* f : {"000000.bin", "000007.bin", "000015.bin"}) {
        const PointCloud scan = read_kitti_bin(dir + "/" + f);
        const SensorGuess g = classify_scan(measure_scan(scan));
        EXPECT_EQ(g.preset, SensorPreset::kHdl64) << f << ": " << g.reason;
        std::cout << f << ": " << g.reason << "\n";
        // Without the order (points shuffled) the elevations merge the HDL-64E's rings: refused
        // (too low for a VLP-16), not taken for a VLP-16.
        PointCloud shuffled = scan;
        std::mt19937 rng(5);
        std::shuffle(shuffled.points.begin(), shuffled.points.end(), rng);
        const SensorGuess s = classify_scan(measure_scan(shuffled));
        EXPECT_NE(s.preset, SensorPreset::kVlp16) << f << " shuffled: " << s.reason;
        std::cout << f << " shuffled: " << s.reason << "\n";
    }
}

TEST(SensorDetect, RealLivoxAviaScansAreNarrow) {
    for (const char* session : {"session1", "session2"}) {
        const std::string dir = kShared + "/hku-avia-2session/" + session + "/Scans";
        if (!std::filesystem::exists(dir + "/000000.pcd"))
            GTEST_SKIP() << "hku-avia-2session not found under ../shared/data";
        for (const char* f : {"000000.pcd", "000100.pcd"}) {
            const SensorGuess g = classify_scan(measure_scan(load_cloud_file(dir + "/" + f)));
            EXPECT_EQ(g.preset, SensorPreset::kNarrow) << session << " " << f << ": " << g.reason;
            std::cout << session << " " << f << ": " << g.reason << "\n";
        }
    }
}

}  // namespace
}  // namespace ltm::common
