#include "places/core/scan_context.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/core/kitti_io.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::places {
namespace {

constexpr double kDeg = M_PI / 180.0;

double angle_diff(double a, double b) { return std::remainder(a - b, 2.0 * M_PI); }

// What the sensor sees when it turns by yaw_deg at the same place: R_candidate_query = Rz(yaw).
std::vector<Eigen::Vector3f> turned(const std::vector<Eigen::Vector3f>& points, double yaw_deg) {
    return registration::test::transformed(points,
                                           registration::test::xy_yaw(0, 0, yaw_deg).inverse());
}

TEST(ScanContext, MaxHeightBinsMatchABruteForceOracle) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(3);
    const std::vector<Eigen::Vector3f> pts =
        registration::test::view(scene, registration::test::xy_yaw(1, 2, 0), 80.0);
    ScanContextConfig cfg;
    const ScanContext sc = make_scan_context(pts, cfg);
    ASSERT_EQ(sc.value.size(), 20u * 60u);
    // Oracle: each point's bin from first principles.
    std::vector<float> oracle(sc.value.size(), -std::numeric_limits<float>::infinity());
    for (const Eigen::Vector3f& p : pts) {
        const double r = std::sqrt(double(p.x()) * p.x() + double(p.y()) * p.y());
        if (r >= 80.0) continue;
        double a = std::atan2(double(p.y()), double(p.x())) / kDeg;
        if (a < 0) a += 360.0;
        const int ring = std::min(19, int(r / 4.0)), sector = std::min(59, int(a / 6.0));
        float& o = oracle[std::size_t(ring) * 60 + sector];
        o = std::max(o, float(p.z() + 2.0));
    }
    int occupied = 0;
    for (std::size_t b = 0; b < oracle.size(); ++b) {
        const bool occ = std::isfinite(oracle[b]);
        ASSERT_EQ(bool(sc.occupied[b]), occ) << "bin " << b;
        if (!occ) {
            EXPECT_EQ(sc.value[b], 0.0f);
            continue;
        }
        ++occupied;
        EXPECT_FLOAT_EQ(sc.value[b], std::max(0.0f, oracle[b])) << "bin " << b;
    }
    EXPECT_GT(occupied, 400);
}

TEST(ScanContext, MeanVarianceBinsMatchABruteForceOracle) {
    const std::vector<Eigen::Vector3f> pts = registration::test::view(
        registration::test::synthetic_scene(4), registration::test::xy_yaw(0, 0, 0), 60.0);
    ScanContextConfig cfg;
    cfg.kind = ScanContextKind::kMeanVariance;
    cfg.rings = 10;
    cfg.sectors = 36;
    cfg.max_range = 60.0;
    const ScanContext sc = make_scan_context(pts, cfg);
    ASSERT_EQ(sc.spread.size(), 360u);
    std::vector<double> s(360, 0.0), s2(360, 0.0), n(360, 0.0);
    for (const Eigen::Vector3f& p : pts) {
        const double r = std::hypot(double(p.x()), double(p.y()));
        double a = std::atan2(double(p.y()), double(p.x())) / kDeg;
        if (a < 0) a += 360.0;
        const std::size_t b =
            std::size_t(std::min(9, int(r / 6.0))) * 36 + std::min(35, int(a / 10.0));
        const double z = p.z() + 2.0;
        s[b] += z;
        s2[b] += z * z;
        n[b] += 1.0;
    }
    for (std::size_t b = 0; b < 360; ++b) {
        ASSERT_EQ(bool(sc.occupied[b]), n[b] > 0) << "bin " << b;
        if (n[b] == 0) continue;
        const double mean = s[b] / n[b];
        EXPECT_NEAR(sc.value[b], mean, 1e-4) << "bin " << b;
        EXPECT_NEAR(sc.spread[b], std::sqrt(std::max(0.0, s2[b] / n[b] - mean * mean)), 1e-3);
    }
}

TEST(ScanContext, RecoversTheYawOfATurnedSensorOnASyntheticScene) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(7);
    const std::vector<Eigen::Vector3f> base =
        registration::test::view(scene, registration::test::xy_yaw(3, -2, 20), 80.0);
    for (const ScanContextKind kind :
         {ScanContextKind::kMaxHeight, ScanContextKind::kMeanVariance}) {
        ScanContextConfig cfg;
        cfg.kind = kind;
        const ScanContext candidate = make_scan_context(base, cfg);
        for (const double yaw : {0.0, 48.0, -114.0, 180.0, 37.0, -161.0}) {
            const ScanContext query = make_scan_context(turned(base, yaw), cfg);
            const ScanContextMatch m = compare(query, candidate, cfg);
            ASSERT_TRUE(m.valid);
            // A multiple of the 6 deg sector is recovered exactly; otherwise to within a sector.
            const double tol = std::fmod(std::abs(yaw), 6.0) == 0.0 ? 1e-9 : 6.0;
            EXPECT_LE(std::abs(angle_diff(m.yaw, yaw * kDeg)) / kDeg, tol)
                << "kind " << int(kind) << " yaw " << yaw << " got " << m.yaw / kDeg;
            // The ring key does not depend on the yaw (exactly so for whole sectors).
            if (tol < 1.0) {
                EXPECT_LT((ring_key(query) - ring_key(candidate)).norm(), 1e-4f);
                EXPECT_LT(m.distance, 1e-6);
            }
        }
    }
}

TEST(ScanContext, BestShiftIsTheMinimumOverAllShifts) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(11);
    ScanContextConfig cfg;
    const ScanContext a = make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(0, 0, 0), 80.0), cfg);
    const ScanContext b = make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(4, 1, 71), 80.0), cfg);
    const ScanContextMatch m = compare(a, b, cfg);
    double oracle = std::numeric_limits<double>::infinity();
    int oracle_shift = -1;
    for (int s = 0; s < 60; ++s) {
        const double d = distance_at_shift(a, b, s, cfg);
        if (d < oracle) {
            oracle = d;
            oracle_shift = s;
        }
    }
    EXPECT_DOUBLE_EQ(m.distance, oracle);
    EXPECT_EQ(m.shift, oracle_shift);
}

TEST(ScanContext, SamePlaceIsCloserThanAnotherPlace) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(5);
    ScanContextConfig cfg;
    const ScanContext here = make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(0, 0, 0), 80.0), cfg);
    const ScanContext near = make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(1.5, 0.5, 150), 80.0), cfg);
    const ScanContext far = make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(45, -40, 0), 80.0), cfg);
    const ScanContextMatch m_near = compare(near, here, cfg), m_far = compare(far, here, cfg);
    EXPECT_LT(m_near.distance, 0.25);
    EXPECT_GT(m_far.distance, m_near.distance + 0.1);
    EXPECT_LE(std::abs(angle_diff(m_near.yaw, 150 * kDeg)) / kDeg, 6.0);
}

TEST(ScanContext, RecoversAKnownYawOnARealKittiFrame) {
    const std::string dir = registration::test::fixture_kitti00();
    const common::PointCloud cloud = common::read_kitti_bin(dir + "/velodyne/000000.bin");
    ASSERT_GT(cloud.size(), 10000u);
    ScanContextConfig cfg;
    cfg.sensor_height = 1.73;
    const ScanContext candidate = make_scan_context(cloud.points, cfg);
    for (const double yaw : {90.0, -30.0, 180.0, 123.0, -77.5}) {
        const ScanContext query = make_scan_context(turned(cloud.points, yaw), cfg);
        const ScanContextMatch full = compare(query, candidate, cfg);
        EXPECT_LE(std::abs(angle_diff(full.yaw, yaw * kDeg)) / kDeg, 6.0) << "yaw " << yaw;
        EXPECT_LT(full.distance, 0.15) << "yaw " << yaw;
        // The fast search (sector key alignment, then a window) finds the same shift here.
        ScanContextConfig fast = cfg;
        fast.shift_search_radius = 3;
        EXPECT_EQ(compare(query, candidate, fast).shift, full.shift) << "yaw " << yaw;
    }
    // The next frame, about 0.7 m on and turned by 123 deg: still a match, yaw within a sector.
    const common::PointCloud next = common::read_kitti_bin(dir + "/velodyne/000002.bin");
    const ScanContextMatch m =
        compare(make_scan_context(turned(next.points, 123.0), cfg), candidate, cfg);
    EXPECT_LE(std::abs(angle_diff(m.yaw, 123.0 * kDeg)) / kDeg, 6.0);
    EXPECT_LT(m.distance, 0.25);
}

TEST(ScanContext, DescriptorsOfDifferentShapesDoNotCompare) {
    ScanContextConfig a, b;
    b.sectors = 30;
    const std::vector<Eigen::Vector3f> pts = {{1, 0, 0}, {0, 5, 1}};
    EXPECT_FALSE(compare(make_scan_context(pts, a), make_scan_context(pts, b), a).valid);
    EXPECT_FALSE(compare(ScanContext(), ScanContext(), a).valid);
    EXPECT_TRUE(
        std::isinf(distance_at_shift(make_scan_context(pts, a), make_scan_context(pts, b), 0, a)));
}

TEST(ScanContext, EmptyAndNonFiniteInputGiveAnEmptyButValidDescriptor) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const ScanContext sc = make_scan_context({{nan, 0, 0}, {1e6f, 0, 0}}, ScanContextConfig());
    EXPECT_EQ(sc.value.size(), 1200u);
    for (std::uint8_t o : sc.occupied) EXPECT_EQ(o, 0);
    EXPECT_EQ(compare(sc, sc, ScanContextConfig()).distance, 1.0);  // nothing in common
}

TEST(ScanContext, ValidateNamesTheKey) {
    EXPECT_FALSE(validate(ScanContextConfig()));
    ScanContextConfig c;
    c.rings = 0;
    ASSERT_TRUE(validate(c));
    EXPECT_EQ(validate(c)->key, "rings");
    EXPECT_EQ(validate(c)->problem, "must be in [1, 1000] (got 0)");
    c = ScanContextConfig();
    c.sensor_height = std::nan("");
    EXPECT_EQ(validate(c)->key, "sensor_height");
    EXPECT_EQ(validate(c)->problem, "must be finite (got nan)");
    c = ScanContextConfig();
    c.empty_bin_cost = std::numeric_limits<double>::infinity();  // an infinite cost is allowed
    EXPECT_FALSE(validate(c));
    c.min_range = 90.0;  // across fields: min_range < max_range
    EXPECT_EQ(validate(c)->key, "min_range");
    EXPECT_EQ(validate(c)->problem, "must be smaller than max_range");
    c = ScanContextConfig();
    c.kind = ScanContextKind(7);
    EXPECT_EQ(validate(c)->key, "kind");
}

}  // namespace
}  // namespace ltm::places
