#include "evaluation/core/kitti_metric.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A straight drive along x, 1 m a frame; the estimate's steps are `scale` m long and its
// orientation rolls `roll_rate` rad a frame about the direction of travel.
void straight(std::size_t frames, double scale, double roll_rate, common::PoseList& est,
              common::PoseList& ref) {
    for (std::size_t i = 0; i < frames; ++i) {
        Eigen::Isometry3d r = Eigen::Isometry3d::Identity(), e = Eigen::Isometry3d::Identity();
        r.translation() = Eigen::Vector3d(static_cast<double>(i), 0, 0);
        e.translation() = Eigen::Vector3d(scale * static_cast<double>(i), 0, 0);
        e.linear() = Eigen::AngleAxisd(roll_rate * static_cast<double>(i), Eigen::Vector3d::UnitX())
                         .matrix();
        ref.push_back(r);
        est.push_back(e);
    }
}

// By hand, for 61 frames (0..60 m) and the 10..50 m lengths: a segment of nominal length L
// starting at f ends at f + L + 1 (the first frame strictly beyond L), so it spans L + 1 frames.
// Counts of first frames 0, 10, ..., with f + L + 1 <= 60: L=10: 5, 20: 4, 30: 3, 40: 2, 50: 1.
// With 1 % too long steps the error is 0.01 (L + 1) / L; the average over the 15 segments is
// (5*0.011 + 4*0.0105 + 3*0.0103333 + 2*0.01025 + 0.0102) / 15 = 0.1587 / 15 = 0.01058.
TEST(KittiMetric, ShortRunScaleErrorByHand) {
    common::PoseList est, ref;
    straight(61, 1.01, 0.0, est, ref);
    const KittiMetric m = compute_kitti_metric(est, ref);
    EXPECT_TRUE(m.short_segments);
    EXPECT_EQ(m.segments, 15u);
    EXPECT_NEAR(m.translation_pct, 100.0 * 0.1587 / 15.0, 1e-9);
    EXPECT_NEAR(m.rotation_deg_per_100m, 0.0, 1e-9);
}

TEST(KittiMetric, ShortRunRotationErrorByHand) {
    // Roll about the direction of travel leaves positions unchanged: translation error 0,
    // rotation error 0.001 (L + 1) / L rad/m, averaged as above: 0.001058 rad/m.
    common::PoseList est, ref;
    straight(61, 1.0, 0.001, est, ref);
    const KittiMetric m = compute_kitti_metric(est, ref);
    EXPECT_NEAR(m.translation_pct, 0.0, 1e-9);
    EXPECT_NEAR(m.rotation_deg_per_100m, 100.0 * 0.1587e-1 / 15.0 * 180.0 / kPi, 1e-6);
}

TEST(KittiMetric, SmallRotationErrorsSurviveRoundedPoseFiles) {
    // Poses as KITTI files hold them: every entry rounded to 7 significant digits. A roll error
    // of 1e-6 rad a frame (about 0.006 deg/100 m) must still come out within a few percent.
    common::PoseList est, ref;
    straight(61, 1.0, 1e-6, est, ref);
    for (auto& T : est)
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                const double v = T.matrix()(r, c);
                if (v != 0.0) {
                    const double scale = std::pow(10.0, 6 - std::floor(std::log10(std::abs(v))));
                    T.matrix()(r, c) = std::round(v * scale) / scale;
                }
            }
    const KittiMetric m = compute_kitti_metric(est, ref);
    const double expected = 100.0 * 0.1587e-1 / 15.0 * 180.0 / kPi * 1e-3;  // 1e-3 x the 0.001 case
    EXPECT_NEAR(m.rotation_deg_per_100m, expected, 0.05 * expected);
}

TEST(KittiMetric, LongRunUsesTheDevkitLengths) {
    // 901 frames (900 m): L = 100 m spans L + 1 frames; first frames f <= 899 - L, step 10.
    common::PoseList est, ref;
    straight(901, 1.01, 0.0, est, ref);
    const KittiMetric m = compute_kitti_metric(est, ref);
    EXPECT_FALSE(m.short_segments);
    // Counts: L=100: f<=799 -> 80, 200: 70, ..., 800: 10; total 360.
    EXPECT_EQ(m.segments, 360u);
    double sum = 0.0;
    for (int k = 1; k <= 8; ++k) sum += (90 - 10 * k) * 0.01 * (100.0 * k + 1) / (100.0 * k);
    EXPECT_NEAR(m.translation_pct, 100.0 * sum / 360.0, 1e-9);
}

TEST(KittiMetric, TooShortRunHasNoSegments) {
    common::PoseList est, ref;
    straight(10, 1.01, 0.0, est, ref);
    const KittiMetric m = compute_kitti_metric(est, ref);
    EXPECT_EQ(m.segments, 0u);
    EXPECT_TRUE(m.short_segments);
}

TEST(KittiMetric, DistancesTravelled) {
    common::PoseList est, ref;
    straight(4, 1.0, 0.0, est, ref);
    const std::vector<double> d = distances_travelled(ref);
    ASSERT_EQ(d.size(), 4u);
    EXPECT_DOUBLE_EQ(d[3], 3.0);
}

}  // namespace
}  // namespace ltm::eval
