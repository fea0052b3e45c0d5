#include "mapping/core/loop_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

TEST(LoopDetector, RecentKeyframesAreExcludedByCount) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(8);
    places::ScanContextConfig sc;
    LoopDetectorConfig cfg;
    cfg.exclude_recent_keyframes = 5;
    cfg.exclude_recent_seconds = 0.0;
    cfg.max_results = 20;
    cfg.candidates = 20;
    LoopDetector d(sc, cfg);
    // The same place again and again: every earlier keyframe would be a candidate.
    const places::ScanContext same = places::make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(0, 0, 0), 80), sc);
    for (std::uint32_t i = 0; i < 12; ++i) {
        std::vector<LoopCandidate> c;
        ASSERT_TRUE(d.add(same, 0, 0.1 * i, &c));
        std::size_t expected = i >= 6 ? i - 5 : 0;  // keyframes with at least 5 newer ones
        EXPECT_EQ(c.size(), expected) << "keyframe " << i;
        for (const LoopCandidate& x : c) {
            EXPECT_LE(x.match + 6, i);
            EXPECT_LT(x.distance, 1e-6);
        }
    }
}

TEST(LoopDetector, RecentKeyframesAreExcludedByTimeButNotAcrossSessions) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(9);
    places::ScanContextConfig sc;
    LoopDetectorConfig cfg;
    cfg.exclude_recent_keyframes = 0;
    cfg.exclude_recent_seconds = 10.0;
    cfg.max_results = 50;
    cfg.candidates = 50;
    LoopDetector d(sc, cfg);
    const places::ScanContext same = places::make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(2, 1, 30), 80), sc);
    std::vector<LoopCandidate> c;
    for (int i = 0; i < 15; ++i) {
        ASSERT_TRUE(d.add(same, 0, 1.0 * i, &c));
        for (const LoopCandidate& x : c) EXPECT_GE(1.0 * i - 1.0 * x.match, 10.0);
    }
    EXPECT_EQ(c.size(), 5u);  // stamps 0..4 are at least 10 s older than 14
    // A new session: every keyframe of the earlier one is searchable at once.
    ASSERT_TRUE(d.add(same, 1, 14.5, &c));
    EXPECT_EQ(c.size(), 15u);
}

// Two robots at once (sessions 0 and 1 interleaved): each finds the other's keyframes as soon as
// they are kept, never its own recent ones.
TEST(LoopDetector, SessionsAtOnceFindEachOthersKeyframesAtOnceAndNotTheirOwnRecentOnes) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(9);
    places::ScanContextConfig sc;
    LoopDetectorConfig cfg;
    cfg.exclude_recent_keyframes = 100;
    cfg.exclude_recent_seconds = 100.0;
    cfg.max_results = 50;
    cfg.candidates = 50;
    LoopDetector d(sc, cfg);
    const places::ScanContext same = places::make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(2, 1, 30), 80), sc);
    for (std::uint32_t i = 0; i < 10; ++i) {
        for (std::uint32_t session = 0; session < 2; ++session) {
            std::vector<LoopCandidate> c;
            ASSERT_TRUE(d.add(same, session, 1.0 * i, &c));
            // The other session's keyframes kept so far (they alternate: 0, 1, 0, 1, ...).
            EXPECT_EQ(c.size(), session == 0 ? i : i + 1) << "keyframe " << i << " of " << session;
            for (const LoopCandidate& x : c) EXPECT_NE(x.match % 2, session);
        }
    }
}

TEST(LoopDetector, FindsATurnedRevisitAndNotAnotherPlace) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(12);
    const std::vector<Eigen::Vector3f> other = registration::test::synthetic_scene(13);
    places::ScanContextConfig sc;
    LoopDetectorConfig cfg;
    cfg.exclude_recent_keyframes = 0;
    cfg.exclude_recent_seconds = 0.0;
    LoopDetector d(sc, cfg);
    std::vector<LoopCandidate> c;
    // A drive along x through the scene.
    for (int i = 0; i < 10; ++i) {
        ASSERT_TRUE(d.add(
            places::make_scan_context(
                registration::test::view(scene, registration::test::xy_yaw(4.0 * i, 0, 0), 80), sc),
            0, i, &c));
    }
    // Back at x = 12 m, facing the other way, 0.8 m to the side.
    const places::ScanContext back = places::make_scan_context(
        registration::test::view(scene, registration::test::xy_yaw(12.3, 0.8, 180), 80), sc);
    const std::vector<LoopCandidate> found = d.query(back);
    ASSERT_FALSE(found.empty());
    EXPECT_EQ(found[0].match, 3u);
    EXPECT_LE(std::abs(std::remainder(found[0].yaw - M_PI, 2 * M_PI)), 6.0 * M_PI / 180.0);
    // Another town: nothing under the threshold.
    EXPECT_TRUE(
        d.query(places::make_scan_context(
                    registration::test::view(other, registration::test::xy_yaw(10, 0, 0), 80), sc))
            .empty());
    // A descriptor of another shape is refused.
    places::ScanContextConfig small = sc;
    small.sectors = 30;
    EXPECT_FALSE(
        d.add(places::make_scan_context(
                  registration::test::view(scene, registration::test::xy_yaw(0, 0, 0), 80), small),
              0, 11, &c));
    EXPECT_EQ(d.size(), 10u);
}

TEST(LoopDetector, InvalidConfigurationNamesTheKey) {
    LoopDetectorConfig cfg;
    cfg.candidates = 0;
    try {
        LoopDetector d(places::ScanContextConfig(), cfg);
        FAIL() << "accepted candidates = 0";
    } catch (const common::ConfigError& e) {
        EXPECT_STREQ(e.what(), "loop_detection.candidates: must be >= 1 (got 0)");
    }
}

}  // namespace
}  // namespace ltm::mapping
