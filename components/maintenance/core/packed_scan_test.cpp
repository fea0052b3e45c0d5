#include "maintenance/core/packed_scan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>

#include "common/core/io_error.hpp"

namespace ltm::maintenance {
namespace {

// A spinning sensor's scan: rings of points on a wall 5-40 m away, with noise (fixed seed).
std::vector<Eigen::Vector3f> sensor_scan(int rings, int columns) {
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 0.02f);
    std::vector<Eigen::Vector3f> points;
    for (int c = 0; c < columns; ++c) {
        const float azimuth = 2.0f * float(M_PI) * float(c) / float(columns);
        const float range = 5.0f + 35.0f * std::abs(std::sin(0.5f * azimuth)) + noise(rng);
        for (int r = 0; r < rings; ++r) {
            const float elevation = -0.4f + 0.8f * float(r) / float(rings - 1);
            points.emplace_back(range * std::cos(elevation) * std::cos(azimuth),
                                range * std::cos(elevation) * std::sin(azimuth),
                                range * std::sin(elevation));
        }
    }
    return points;
}

bool same_bits(const std::vector<Eigen::Vector3f>& a, const std::vector<Eigen::Vector3f>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Eigen::Vector3f)) == 0);
}

TEST(PackedScan, GivesBackTheSamePointsBitForBit) {
    const std::vector<Eigen::Vector3f> points = sensor_scan(32, 1800);
    const PackedScan packed = pack_points(points);
    EXPECT_EQ(packed.count, points.size());
    EXPECT_TRUE(same_bits(unpack_points(packed), points));
    // Smaller than the points it holds (a scan of a smooth wall: well under 12 B a point).
    EXPECT_LT(packed.memory_bytes(), points.size() * sizeof(Eigen::Vector3f));
}

TEST(PackedScan, KeepsNonFiniteValuesNegativeZeroAndAnEmptyScan) {
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<Eigen::Vector3f> odd = {
        {std::nanf(""), 1.0f, -0.0f}, {inf, -inf, 3.5f}, {-1e-38f, 1e38f, 0.0f}};
    EXPECT_TRUE(same_bits(unpack_points(pack_points(odd)), odd));
    EXPECT_TRUE(unpack_points(pack_points({})).empty());
}

TEST(PackedScan, DamagedBytesAreAOneLineFormatError) {
    PackedScan packed = pack_points(sensor_scan(4, 100));
    PackedScan wrong_count = packed;
    wrong_count.count += 1;
    EXPECT_THROW(unpack_points(wrong_count), common::FormatError);
    PackedScan cut = packed;
    cut.bytes.resize(cut.bytes.size() / 2);
    EXPECT_THROW(unpack_points(cut), common::FormatError);
    PackedScan garbage = packed;
    for (std::uint8_t& b : garbage.bytes) b = 0x5a;
    try {
        unpack_points(garbage);
        FAIL() << "garbage unpacked";
    } catch (const common::FormatError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
}

TEST(PackedScan, RefusesALevelOutOfRange) {
    EXPECT_THROW(pack_points({}, 0), std::invalid_argument);
    EXPECT_THROW(pack_points({}, 100), std::invalid_argument);
}

}  // namespace
}  // namespace ltm::maintenance
