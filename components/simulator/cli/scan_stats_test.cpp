#include "simulator/cli/scan_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::sim::cli {
namespace {

// A synthetic KITTI-ordered scan: `rings` rings, each from azimuth 0 round counter-clockwise.
common::PointCloud kitti_ordered(int rings, int per_ring, double range) {
    common::PointCloud c;
    for (int r = 0; r < rings; ++r) {
        const double el = (2.0 - r) * M_PI / 180.0;
        for (int k = 0; k < per_ring; ++k) {
            const double az = 2 * M_PI * k / per_ring;
            c.points.emplace_back(float(range * std::cos(el) * std::cos(az)),
                                  float(range * std::cos(el) * std::sin(az)),
                                  float(range * std::sin(el)));
            c.intensity.push_back(0.25f);
        }
    }
    return c;
}

TEST(ScanStats, RecoversRingsFromKittiOrder) {
    const common::PointCloud c = kitti_ordered(8, 500, 12.0);
    const std::vector<int> rings = rings_from_order(c);
    for (std::size_t i = 0; i < rings.size(); ++i) ASSERT_EQ(rings[i], static_cast<int>(i / 500));
    const ScanStats s = scan_stats(c, {0, 10, 20});
    EXPECT_EQ(s.points, 4000u);
    ASSERT_EQ(s.ring_points.size(), 8u);
    EXPECT_DOUBLE_EQ(s.ring_points[3], 500.0);
    EXPECT_NEAR(s.ring_elevation[5], -3.0, 1e-4);
    EXPECT_DOUBLE_EQ(s.range_fraction[1], 1.0);  // all at 12 m
    EXPECT_NEAR(s.range_median, 12.0, 1e-4);
    EXPECT_NEAR(s.intensity_pct[2], 0.25, 1e-6);
    const ScanStats m = average_stats({s, scan_stats(kitti_ordered(8, 300, 25.0), {0, 10, 20})});
    EXPECT_DOUBLE_EQ(m.ring_points[0], 400.0);
    EXPECT_DOUBLE_EQ(m.range_fraction[2], 0.5);
    const std::string table = compare_table({s, m}, {"a", "b"});
    EXPECT_NE(table.find("ring  7"), std::string::npos);
    EXPECT_NE(table.find("4000"), std::string::npos);
}

}  // namespace
}  // namespace ltm::sim::cli
