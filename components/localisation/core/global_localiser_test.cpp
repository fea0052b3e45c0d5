// Global localisation on maps of many laps (issue 26 item 6, issue 27 item 4): the ring-key
// candidates of a place held many times over, and the guesses that settle at an answer already
// verified. Synthetic scene, exact truth (localiser_test_scene.hpp).
#include "localisation/core/global_localiser.hpp"

#include <gtest/gtest.h>

#include "localisation/core/localiser.hpp"
#include "localisation/core/localiser_test_scene.hpp"

namespace ltm::localisation {
namespace {

using namespace test_scene;

// The scene's path map with the keyframe of path[i] held `copies` more times (the laps of a
// folded map over one place).
std::shared_ptr<const LocalisationMap> lapped_map(const SceneMap& s, std::size_t i, int copies) {
    std::vector<std::vector<Eigen::Vector3f>> scans;
    common::PoseList poses;
    for (const Eigen::Isometry3d& T : s.path) {
        poses.push_back(T);
        scans.push_back(mt::view(s.scene, T, 60.0));
    }
    for (int c = 0; c < copies; ++c) {
        poses.push_back(s.path[i]);
        scans.push_back(scans[i]);
    }
    return std::make_shared<const LocalisationMap>(make_map(scans, poses, 0.6, 0.0));
}

TEST(GlobalLocaliserCandidates, ThePlacesOfALappedMapAreNotOnePlaceManyTimes) {
    const SceneMap& s = scene_map();
    const auto map = lapped_map(s, 8, 12);
    const std::vector<Eigen::Vector3f> scan =
        mt::view(s.scene, s.path[8] * mt::xy_yaw(0.5, 0.3, 40.0), 60.0);
    GlobalLocaliserConfig few;
    few.candidates = 6;
    few.local_features = false;
    // Every one of the 6 nearest ring keys is the one place (13 times in the map): one place.
    GlobalLocaliserConfig clumped = few;
    clumped.candidate_separation = 0.0;
    const GlobalLocalisation a = GlobalLocaliser(map, clumped).localise(scan);
    EXPECT_EQ(a.places, 1) << a.reason;
    // Skipping the neighbours within candidate_separation of a nearer one, the 6 candidates span
    // the path: several places to verify.
    const GlobalLocalisation b = GlobalLocaliser(map, few).localise(scan);
    EXPECT_GE(b.places, 3) << b.reason;
    // The pool and the separation are checked keys.
    GlobalLocaliserConfig bad;
    bad.candidate_separation = -1.0;
    ASSERT_TRUE(validate(bad));
    EXPECT_EQ(validate(bad)->key, "candidate_separation");
    bad = GlobalLocaliserConfig();
    bad.candidate_pool = 0;
    EXPECT_EQ(validate(bad)->key, "candidate_pool");
}

// A narrow view's keyframes a few metres apart, or turned, see different things (hku-avia's
// handheld map, 149 keyframes 0.4 m apart: 8 scans refused when its ring-key neighbours were
// skipped as clumps of one place, 250 -> 257 of 266 right without): its preset compares every
// neighbour; a spinning sensor's presets skip the clumps.
TEST(GlobalLocaliserCandidates, ANarrowViewsNeighboursAreNotSkippedAsClumps) {
    const SceneMap& s = scene_map();
    const auto map = lapped_map(s, 8, 12);
    const std::vector<Eigen::Vector3f> scan =
        mt::view(s.scene, s.path[8] * mt::xy_yaw(0.5, 0.3, 40.0), 60.0);
    for (const common::SensorPreset preset : common::kSensorPresets) {
        GlobalLocaliserConfig c = localiser_preset(preset).global;
        c.candidates = 6;
        c.local_features = false;
        const GlobalLocalisation a = GlobalLocaliser(map, c).localise(scan);
        const bool narrow = common::sensor_preset_row(preset).horizontal_fov_deg < 360.0;
        if (narrow) {
            EXPECT_EQ(a.places, 1) << common::sensor_preset_row(preset).name << ": " << a.reason;
        } else {
            EXPECT_GE(a.places, 3) << common::sensor_preset_row(preset).name << ": " << a.reason;
        }
    }
    EXPECT_EQ(localiser_preset(common::SensorPreset::kNarrow).global.candidate_separation, 0.0);
}

TEST(GlobalLocaliserRivals, GuessesThatSettleAtTheAnswerOrProbeFarWorseAreNotVerified) {
    const SceneMap& s = scene_map();
    GlobalLocaliserConfig every;  // every guess the probes let through is verified
    every.rival_settle_iterations = 0;
    every.rival_answer_probe_ratio = 0.0;
    GlobalLocaliserConfig settle = every;
    settle.rival_settle_iterations = 30;
    GlobalLocaliser all(s.map, every), settling(s.map, settle), defaults(s.map);
    int settled = 0, outprobed = 0, verified_all = 0, verified_settling = 0, verified_default = 0;
    for (int trial = 0; trial < 5; ++trial) {
        const Eigen::Isometry3d truth =
            s.path[std::size_t(3 + 2 * trial)] * mt::xy_yaw(1.0, -1.0, 30.0 + 50.0 * trial);
        const std::vector<Eigen::Vector3f> scan = mt::view(s.scene, truth, 60.0);
        const GlobalLocalisation a = all.localise(scan);
        const GlobalLocalisation b = settling.localise(scan);
        const GlobalLocalisation c = defaults.localise(scan);
        ASSERT_EQ(a.localised, b.localised) << trial << ": " << a.reason << " / " << b.reason;
        ASSERT_EQ(a.localised, c.localised) << trial << ": " << a.reason << " / " << c.reason;
        if (!a.localised) continue;
        // The same answer, with fewer verifications.
        EXPECT_LT(error_of(b.T_map_lidar, a.T_map_lidar).translation, 0.01) << trial;
        EXPECT_LT(error_of(c.T_map_lidar, a.T_map_lidar).translation, 0.01) << trial;
        EXPECT_LT(error_of(c.T_map_lidar, truth).translation, 0.1) << trial;
        EXPECT_EQ(a.settled + a.outprobed + b.outprobed, 0);
        settled += b.settled;
        outprobed += c.outprobed;
        verified_all += a.verified;
        verified_settling += b.verified;
        verified_default += c.verified;
    }
    // A settled guess is one verification fewer, and would have verified to the answer.
    EXPECT_GT(settled, 0);
    EXPECT_EQ(verified_settling + settled, verified_all);
    EXPECT_GT(outprobed, 0);
    EXPECT_LT(verified_default, verified_settling);
}

TEST(GlobalLocaliserSearch, TurnsOnlyTheGuessesThatDidNotVerify) {
    const SceneMap& s = scene_map();
    const std::vector<Eigen::Vector3f> scan =
        mt::view(s.scene, s.path[6] * mt::xy_yaw(0.4, -0.3, 25.0), 60.0);
    GlobalLocaliserConfig c;
    c.local_features = false;
    c.verify_best = 1;  // one guess verified, and searched around
    c.search.yaw_offsets = {-3.0, 0.0, 3.0};
    // One yaw: the start and the 80 other offsets within 5 m on a 1 m grid.
    const int one_yaw = 81, three_yaws = 1 + 80 + 2 * 81;
    // A guess that verified (the search run anyway: every fit is below 1.0): searched at its
    // own heading only, as before the yaw offsets came (the KITTI 04 snippet's cost).
    GlobalLocaliserConfig after_answer = c;
    after_answer.search.below_inlier_fraction = 1.0;
    const GlobalLocalisation a = GlobalLocaliser(s.map, after_answer).localise(scan);
    ASSERT_TRUE(a.localised) << a.reason;
    EXPECT_EQ(a.searched, 1);
    EXPECT_EQ(a.search_scored, one_yaw);
    // A guess that did not verify: searched at the three yaws.
    GlobalLocaliserConfig refused = c;
    refused.verification.min_inlier_fraction = 1.0;
    refused.verification.max_inlier_rms = 1e-9;
    const GlobalLocalisation b = GlobalLocaliser(s.map, refused).localise(scan);
    EXPECT_FALSE(b.localised);
    EXPECT_EQ(b.searched, 1);
    EXPECT_EQ(b.search_scored, three_yaws);
}

}  // namespace
}  // namespace ltm::localisation
