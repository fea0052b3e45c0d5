#include "maintenance/core/range_image.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::maintenance {
namespace {

// A 16-beam scan (+-15 deg, 2 deg apart) of a wall at x = 10 m.
std::vector<Eigen::Vector3f> wall_scan() {
    std::vector<Eigen::Vector3f> pts;
    for (int ring = 0; ring < 16; ++ring) {
        const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0;
        for (int k = 0; k < 1800; ++k) {
            const double az = (-180.0 + 0.2 * k) * M_PI / 180.0;
            const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                    std::sin(el));
            if (d.x() < 0.2) continue;  // the wall is only ahead
            pts.push_back((d * (10.0 / d.x())).cast<float>());
        }
    }
    return pts;
}

TEST(RangeImage, SurfaceFreeOccludedUnseen) {
    const RangeImage image(RangeImageConfig{}, wall_scan());
    ASSERT_FALSE(image.empty());
    const float size = 0.5f, margin = 0.5f;
    EXPECT_EQ(image.classify({10.0f, 0.0f, 0.0f}, size, margin), Visibility::kSurface);
    EXPECT_EQ(image.classify({5.0f, 0.5f, 0.0f}, size, margin), Visibility::kFree);
    EXPECT_EQ(image.classify({15.0f, 0.0f, 0.0f}, size, margin), Visibility::kOccluded);
    // No return behind the sensor: below the horizon nothing is said, above it is sky.
    EXPECT_EQ(image.classify({-5.0f, 0.0f, -1.0f}, size, margin), Visibility::kUnseen);
    EXPECT_EQ(image.classify({-5.0f, 0.0f, 0.0f}, size, margin), Visibility::kFree);
    RangeImageConfig no_sky;
    no_sky.sky_range = 0.0;
    EXPECT_EQ(RangeImage(no_sky, wall_scan()).classify({-5.0f, 0.0f, 0.0f}, size, margin),
              Visibility::kUnseen);
    EXPECT_EQ(image.classify({5.0f, 0.0f, 4.0f}, size, margin), Visibility::kUnseen);  // above
    // Between two beams (2 deg apart, 0.17 m at 5 m): a small cube there is not seen.
    const float between = float(5.0 * std::tan(-12.0 * M_PI / 180.0));
    EXPECT_EQ(image.classify({5.0f, 0.0f, between}, 0.1f, margin), Visibility::kUnseen);
    EXPECT_EQ(image.classify({5.0f, 0.0f, between}, 0.3f, margin), Visibility::kFree);
}

// A 16-beam scan (+-15 deg, 2 deg apart) from 1 m above flat ground: the downward beams hit the
// ground (but for a dark patch at azimuth 20..30 deg that returns nothing), the upward ones
// go to the sky but for a building wall at y = -8 m (azimuth -100..-80 deg, one lost return on
// the +5 deg beam at azimuth -90). `fence`: a 4 m wide fence 2 m high at x = 10 m (its top 1 m
// above the sensor).
std::vector<Eigen::Vector3f> yard_scan(bool fence) {
    std::vector<Eigen::Vector3f> pts;
    for (int ring = 0; ring < 16; ++ring) {
        const double el_deg = -15.0 + 2.0 * ring, el = el_deg * M_PI / 180.0;
        for (int k = 0; k < 1800; ++k) {
            const double az_deg = -180.0 + 0.2 * k + 0.1, az = az_deg * M_PI / 180.0;
            const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                    std::sin(el));
            double t = 1e9;  // the nearest surface along the beam
            if (d.z() < 0.0 && (az_deg < 20.0 || az_deg > 30.0)) t = std::min(t, -1.0 / d.z());
            if (az_deg > -100.0 && az_deg < -80.0 && !(ring == 10 && std::abs(az_deg + 90) < 0.15))
                t = std::min(t, -8.0 / d.y());
            if (fence && d.x() > 0.0) {
                const Eigen::Vector3d q = d * (10.0 / d.x());
                if (std::abs(q.y()) < 2.0 && q.z() > -1.0 && q.z() < 1.0)
                    t = std::min(t, 10.0 / d.x());
            }
            if (t < 100.0) pts.push_back((d * t).cast<float>());
        }
    }
    return pts;
}

TEST(RangeImage, SkyBehindARemovedObjectIsFree) {
    const float size = 0.25f, margin = 0.6f;
    const Eigen::Vector3f fence_top(10.0f, 0.0f, 0.9f), fence_low(10.0f, 0.0f, -0.5f);
    const RangeImage before(RangeImageConfig{}, yard_scan(true));
    EXPECT_EQ(before.classify(fence_top, size, margin), Visibility::kSurface);
    // The fence taken down: its upper half has sky behind it, its lower half the ground.
    const RangeImage after(RangeImageConfig{}, yard_scan(false));
    EXPECT_GT(after.sky_pixels(), 0u);
    EXPECT_EQ(after.classify(fence_top, size, margin), Visibility::kFree);
    EXPECT_EQ(after.classify(fence_low, size, margin), Visibility::kFree);
    EXPECT_EQ(after.classify({60.0f, 0.0f, 8.0f}, size, margin), Visibility::kUnseen)
        << "beyond sky_range (50 m) a sky beam says nothing";
    // Off, the upper half is never judged (what the maintenance did before).
    RangeImageConfig off;
    off.sky_range = 0.0;
    const RangeImage no_sky(off, yard_scan(false));
    EXPECT_EQ(no_sky.sky_pixels(), 0u);
    EXPECT_EQ(no_sky.classify(fence_top, size, margin), Visibility::kUnseen);
    EXPECT_EQ(no_sky.classify(fence_low, size, margin), Visibility::kFree);
}

TEST(RangeImage, NoReturnBelowTheHorizonOrBesideOneSaysNothing) {
    const float size = 0.25f, margin = 0.6f;
    const RangeImage image(RangeImageConfig{}, yard_scan(false));
    // The dark patch below the horizon: no return there is not free space.
    const float a = float(25.0 * M_PI / 180.0);
    EXPECT_EQ(image.classify({4.0f * std::cos(a), 4.0f * std::sin(a), -0.5f}, size, margin),
              Visibility::kUnseen);
    // A return lost on the wall above the horizon: the wall's returns around it, so a small cube
    // of the wall seen only by the lost beams is not free, the space before it is.
    const float z = float(8.0 * std::tan(5.0 * M_PI / 180.0));
    EXPECT_EQ(image.classify({0.0f, -8.0f, z}, 0.05f, margin), Visibility::kUnseen);
    EXPECT_EQ(image.classify({0.0f, -4.0f, 0.5f * z}, 0.05f, margin), Visibility::kFree);
    RangeImageConfig alone;  // without the clearance the lost return would look like sky
    alone.sky_clearance = 0.0;
    EXPECT_EQ(RangeImage(alone, yard_scan(false)).classify({0.0f, -8.0f, z}, 0.05f, margin),
              Visibility::kFree);
    // The sensor pitched 6 deg down: its +5 deg beam points below the world's horizon and the
    // fence top's pixels are ground you cannot see, not sky.
    const float pitch = float(6.0 * M_PI / 180.0);
    const Eigen::Vector3f up(-std::sin(pitch), 0.0f, std::cos(pitch));  // world z, sensor frame
    const RangeImage pitched(RangeImageConfig{}, yard_scan(false), up);
    EXPECT_EQ(pitched.classify({10.0f, 0.0f, 0.9f}, size, margin), Visibility::kUnseen);
    EXPECT_EQ(pitched.classify({-10.0f, 0.0f, 0.9f}, size, margin), Visibility::kFree)
        << "behind the sensor the same beam points 11 deg up";
}

TEST(RangeImage, EmptyAndNonFiniteScans) {
    const RangeImage empty(RangeImageConfig{}, {});
    EXPECT_TRUE(empty.empty());
    EXPECT_EQ(empty.classify({1, 2, 3}, 0.5f, 0.5f), Visibility::kUnseen);
    const float nan = std::nanf("");
    const RangeImage bad(RangeImageConfig{}, {{nan, 0, 0}, {0.1f, 0, 0}});  // NaN, too near
    EXPECT_TRUE(bad.empty());
    const RangeImage image(RangeImageConfig{}, wall_scan());
    EXPECT_EQ(image.classify({nan, 0, 0}, 0.5f, 0.5f), Visibility::kUnseen);
}

}  // namespace
}  // namespace ltm::maintenance
