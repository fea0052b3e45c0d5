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
    EXPECT_EQ(image.classify({-5.0f, 0.0f, 0.0f}, size, margin), Visibility::kUnseen);  // no return
    EXPECT_EQ(image.classify({5.0f, 0.0f, 4.0f}, size, margin), Visibility::kUnseen);   // above
    // Between two beams (2 deg apart, 0.17 m at 5 m): a small cube there is not seen.
    const float between = float(5.0 * std::tan(-12.0 * M_PI / 180.0));
    EXPECT_EQ(image.classify({5.0f, 0.0f, between}, 0.1f, margin), Visibility::kUnseen);
    EXPECT_EQ(image.classify({5.0f, 0.0f, between}, 0.3f, margin), Visibility::kFree);
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
