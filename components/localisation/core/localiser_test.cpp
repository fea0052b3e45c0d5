// Global localisation and tracking on maps built in the test: a synthetic scene (exact truth) and
// the repository's real KITTI fixture (3 frames of sequence 00 with SemanticKITTI poses).
#include "localisation/core/localiser.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/core/config_check.hpp"
#include "common/core/io_error.hpp"
#include "localisation/core/global_localiser.hpp"
#include "localisation/core/localisation_map.hpp"
#include "localisation/core/localiser_test_scene.hpp"
#include "map/core/map_store.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::localisation {
namespace {

using namespace test_scene;

TEST(LocalisationMap, MergesTheVoxelsAndPlacesEveryKeyframe) {
    const SceneMap& s = scene_map();
    EXPECT_EQ(s.map->keyframes().size(), s.path.size());
    EXPECT_GT(s.map->voxels().voxels.size(), 1000u);
    EXPECT_FALSE(s.map->descriptors_computed());
    for (std::size_t i = 0; i < s.path.size(); ++i) {
        EXPECT_LT(error_of(s.map->keyframes()[i].T_map_lidar, s.path[i]).translation, 1e-9);
    }
    EXPECT_GT(s.map->feature_count(), 20u);
}

TEST(LocalisationMap, RefusesAMapWithNothingToLocaliseAgainst) {
    map::MapData empty;
    try {
        LocalisationMap m(empty);
        FAIL() << "an empty map was accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("no keyframes"), std::string::npos) << e.what();
    }
}

TEST(LocalisationMap, FormatOneMapsGetTheirDescriptorsFromTheVoxels) {
    const SceneMap& s = scene_map();
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (const Eigen::Isometry3d& T : s.path) scans.push_back(mt::view(s.scene, T, 60.0));
    map::MapData m = make_map(scans, s.path, 0.6, 0.0);
    m.localisation_descriptor_config = map::no_localisation_descriptors();
    std::vector<std::shared_ptr<const map::StoredKeyframe>> stripped;
    for (const auto& k : m.keyframes) {
        auto c = std::make_shared<map::StoredKeyframe>(*k);
        c->localisation_descriptor = places::ScanContext();
        stripped.push_back(c);
    }
    m.keyframes = stripped;
    LocalisationMapConfig config;
    config.descriptor = descriptor_config(0.0);
    const LocalisationMap map(m, config);
    EXPECT_TRUE(map.descriptors_computed());
    for (const MapKeyframe& k : map.keyframes()) EXPECT_FALSE(k.descriptor.empty());
}

TEST(GlobalLocaliser, FindsATurnedAndShiftedScanOfTheSceneWithNoPrior) {
    const SceneMap& s = scene_map();
    GlobalLocaliser g(s.map);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int found = 0;
    for (int trial = 0; trial < 6; ++trial) {
        // Somewhere along the mapped path, a random heading, up to 3 m off the path.
        const Eigen::Isometry3d& base = s.path[std::size_t(2 + 2 * trial)];
        const Eigen::Isometry3d truth =
            base * mt::xy_yaw(3.0 * u(rng), 3.0 * u(rng), 180.0 * u(rng));
        const GlobalLocalisation r = g.localise(mt::view(s.scene, truth, 60.0));
        if (!r.localised) continue;  // allowed, but a pose must be right
        const Errors e = error_of(r.T_map_lidar, truth);
        EXPECT_LT(e.translation, 0.1) << trial << ": " << r.reason;
        EXPECT_LT(e.rotation_deg, 0.5) << trial << ": " << r.reason;
        EXPECT_GT(r.confidence, 0.0);
        ++found;
    }
    EXPECT_GE(found, 5);
}

TEST(GlobalLocaliser, AnswersNotLocalisedForAPlaceThatIsNotInTheMap) {
    const SceneMap& s = scene_map();
    GlobalLocaliser g(s.map);
    const std::vector<Eigen::Vector3f> elsewhere =
        mt::with_dense_ground(mt::synthetic_scene(97, 70.0));
    for (const double yaw : {0.0, 120.0}) {
        const GlobalLocalisation r = g.localise(mt::view(elsewhere, mt::xy_yaw(0, 0, yaw), 60.0));
        EXPECT_FALSE(r.localised) << "claimed " << r.T_map_lidar.translation().transpose() << ": "
                                  << r.reason;
        EXPECT_FALSE(r.reason.empty());
    }
    // Nothing at all, and garbage: an answer, not a crash.
    EXPECT_FALSE(g.localise({}).localised);
    EXPECT_FALSE(
        g.localise(std::vector<Eigen::Vector3f>(500, Eigen::Vector3f::Constant(NAN))).localised);
}

TEST(GlobalLocaliser, AHintNarrowsTheSearchToItsPlace) {
    const SceneMap& s = scene_map();
    GlobalLocaliser g(s.map);
    const Eigen::Isometry3d truth = s.path[9] * mt::xy_yaw(1.0, -1.0, 20.0);
    PoseHint hint;
    hint.T_map_lidar = truth * mt::xy_yaw(0.8, 0.5, 10.0);
    hint.radius = 5.0;
    const GlobalLocalisation r = g.localise(mt::view(s.scene, truth, 60.0), hint);
    ASSERT_TRUE(r.localised) << r.reason;
    EXPECT_LT(error_of(r.T_map_lidar, truth).translation, 0.1);
}

TEST(GlobalLocaliser, TheSlideTestRunsOnlyWhereTheFitIsWeakAndFineOnlyGivesTheSamePose) {
    const SceneMap& s = scene_map();
    const Eigen::Isometry3d truth = s.path[7] * mt::xy_yaw(1.0, -1.5, 60.0);
    const std::vector<Eigen::Vector3f> scan = mt::view(s.scene, truth, 60.0);
    GlobalLocaliserConfig always;
    always.slide_below_share = 1.0;
    always.fine_only = false;
    always.slide_settle_iterations = 0;  // every slide pose verified in full
    GlobalLocaliser reference(s.map, always);
    const GlobalLocalisation a = reference.localise(scan);
    ASSERT_TRUE(a.localised) << a.reason;
    EXPECT_TRUE(a.slide_tested);
    // The synthetic scene pins both horizontal directions: the weakest one holds a large share
    // of the information, so the default skips the slide test, and verifies fine-only.
    GlobalLocaliser g(s.map);
    const GlobalLocalisation b = g.localise(scan);
    ASSERT_TRUE(b.localised) << b.reason;
    EXPECT_GT(b.weakest_share, g.config().slide_below_share);
    EXPECT_FALSE(b.slide_tested);
    EXPECT_EQ(b.slide_settled, 0);
    EXPECT_LT(b.verified, a.verified);
    EXPECT_LT(error_of(b.T_map_lidar, a.T_map_lidar).translation, 0.01);
    EXPECT_LT(error_of(b.T_map_lidar, truth).translation, 0.1);
    EXPECT_TRUE(b.covariance.allFinite());
    EXPECT_GT(b.covariance(0, 0), 0.0);
    // Out-of-range keys are refused, naming the key.
    GlobalLocaliserConfig bad;
    bad.fine_only_probe_share = 1.5;
    const auto problem = validate(bad);
    ASSERT_TRUE(problem);
    EXPECT_EQ(problem->key, "fine_only_probe_share");
}

TEST(Localiser, TracksAndRelocalisesAfterAKidnap) {
    const SceneMap& s = scene_map();
    Localiser loc(s.map);
    // The odometry frame differs from the map's by an unknown transform.
    const Eigen::Isometry3d T_odom_map = mt::xy_yaw(40.0, -7.0, 73.0);
    double stamp = 100.0;
    int tracked = 0, relocalised = 0;
    auto step = [&](const Eigen::Isometry3d& truth, std::uint32_t segment,
                    const Eigen::Isometry3d& odom_error) {
        OdometryInput o;
        o.T_odom_lidar = odom_error * T_odom_map * truth;
        o.segment = segment;
        const LocalisationUpdate u = loc.process(stamp, mt::view(s.scene, truth, 60.0), o);
        stamp += 0.1;
        tracked += u.state == LocalisationState::kTracking;
        relocalised += u.state == LocalisationState::kRelocalised;
        return u;
    };
    // Unknown start, then tracking along the path.
    LocalisationUpdate u;
    for (int i = 2; i <= 6; ++i) {
        const Eigen::Isometry3d truth = s.path[std::size_t(i)] * mt::xy_yaw(0.3, 0.4, 0.0);
        u = step(truth, 0, Eigen::Isometry3d::Identity());
        ASSERT_TRUE(u.pose_valid) << i << ": " << u.message;
        EXPECT_LT(error_of(u.T_map_lidar, truth).translation, 0.1) << i;
        EXPECT_LT(error_of(u.T_map_odom, T_odom_map.inverse()).translation, 0.1) << i;
    }
    EXPECT_EQ(relocalised, 1);
    EXPECT_EQ(tracked, 4);
    // Kidnap: carried to another part of the map, the odometry goes on as if nothing happened
    // (its frame no longer agrees with the map there).
    bool back = false;
    int scans_to_relocalise = 0;
    for (int i = 0; i < 12 && !back; ++i) {
        ++scans_to_relocalise;
        const Eigen::Isometry3d truth = s.path[std::size_t(12 + i % 3)] * mt::xy_yaw(0.2, 0.0, 0.0);
        // The odometry believes it is still near path[6].
        const Eigen::Isometry3d believed = T_odom_map * s.path[6];
        OdometryInput o;
        o.T_odom_lidar = believed;
        o.segment = 0;
        u = loc.process(stamp, mt::view(s.scene, truth, 60.0), o);
        stamp += 0.1;
        if (u.state == LocalisationState::kRelocalised) {
            EXPECT_LT(error_of(u.T_map_lidar, truth).translation, 0.1) << u.message;
            back = true;
        } else {
            EXPECT_TRUE(u.state == LocalisationState::kTracking ||
                        u.state == LocalisationState::kLost)
                << to_string(u.state);
            if (u.pose_valid) {
                EXPECT_NE(u.message.find("tracking failed"), std::string::npos) << u.message;
            }
        }
    }
    EXPECT_TRUE(back) << "not relocalised after the kidnap: " << u.message;
    // Lost after lost_after (0.5 s = 5 scans at 10 Hz), relocalised by the next global query.
    EXPECT_LE(scans_to_relocalise, 8);
    // An odometry restart (new segment) is a kidnap announced: relocalised on that scan.
    const Eigen::Isometry3d truth = s.path[4];
    u = step(truth, 1, mt::xy_yaw(-3.0, 5.0, 40.0));
    EXPECT_EQ(u.state, LocalisationState::kRelocalised) << u.message;
    EXPECT_LT(error_of(u.T_map_lidar, truth).translation, 0.1);
}

// Scans at path[2..5] with their odometry (the map's path in the odom frame T_odom_map),
// 0.1 s apart from *stamp: true when each has a pose.
bool track_path_start(Localiser& loc, const SceneMap& s, double* stamp,
                      const Eigen::Isometry3d& T_odom_map = Eigen::Isometry3d::Identity()) {
    for (int i = 2; i <= 5; ++i) {
        const Eigen::Isometry3d& T = s.path[std::size_t(i)];
        const LocalisationUpdate u =
            loc.process(*stamp, mt::view(s.scene, T, 60.0), OdometryInput{T_odom_map * T, 0});
        *stamp += 0.1;
        if (!u.pose_valid) {
            ADD_FAILURE() << "scan " << i << ": " << u.message;
            return false;
        }
    }
    return true;
}

// The map's edge: a scan of which the map explains less than edge_overlap (here half of it is
// structure the map never saw) is not registered; the pose follows the odometry from the last
// scan the map covered (off the map), and tracking resumes where the map covers the scan again.
TEST(Localiser, AtTheMapsEdgeThePoseFollowsTheOdometry) {
    const SceneMap& s = scene_map();
    // Unmapped structure: a grid of points 1 m apart (each survives the 1 m down-sampling) far
    // above anything the map has.
    std::vector<Eigen::Vector3f> unmapped;
    for (int x = -20; x < 20; ++x)
        for (int y = -20; y < 20; ++y)
            for (int z = 25; z < 35; ++z) unmapped.emplace_back(x, y, z);
    for (const double edge : {0.0, 0.7}) {
        LocaliserConfig c;
        c.edge_overlap = edge;
        Localiser loc(s.map, c);
        double stamp = 100.0;
        ASSERT_TRUE(track_path_start(loc, s, &stamp));
        LocalisationUpdate u;
        // At path[6]: the odometry 0.15 m off along the way, half the scan unmapped.
        const Eigen::Isometry3d truth = s.path[6];
        OdometryInput o;
        o.T_odom_lidar = truth * mt::xy_yaw(0.15, 0.0, 0.0);
        std::vector<Eigen::Vector3f> scan = mt::view(s.scene, truth, 60.0);
        scan.insert(scan.end(), unmapped.begin(), unmapped.end());
        u = loc.process(stamp, scan, o);
        stamp += 0.1;
        ASSERT_TRUE(u.pose_valid) << u.message;
        EXPECT_GT(u.overlap, c.min_overlap) << u.message;
        EXPECT_LT(u.overlap, 0.7) << u.message;
        if (edge == 0.0) {
            // Registered: the map corrects the odometry.
            EXPECT_EQ(u.state, LocalisationState::kTracking) << u.message;
            EXPECT_LT(error_of(u.T_map_lidar, truth).translation, 0.05) << u.message;
        } else {
            EXPECT_EQ(u.state, LocalisationState::kOffMap) << u.message;
            EXPECT_NE(u.message.find("map's edge"), std::string::npos) << u.message;
            EXPECT_NEAR(error_of(u.T_map_lidar, truth).translation, 0.15, 0.03) << u.message;
            EXPECT_EQ(u.confidence, 0.0);
            // The map covers the next scan again: tracked, corrected.
            u = loc.process(stamp, mt::view(s.scene, s.path[7], 60.0),
                            OdometryInput{s.path[7] * mt::xy_yaw(0.15, 0.0, 0.0), 0});
            EXPECT_EQ(u.state, LocalisationState::kTracking) << u.message;
            EXPECT_LT(error_of(u.T_map_lidar, s.path[7]).translation, 0.05) << u.message;
        }
    }
}

// The map's edge seen in one direction only (edge_sector_overlap): ahead of the sensor, structure
// the map never saw; the scan as a whole is still mostly explained (overall overlap above 0.5),
// but the sector ahead is not. Without the rule it is tracked; with it, it is at the map's edge.
TEST(Localiser, AtTheMapsEdgeAheadOnlyThePoseFollowsTheOdometry) {
    const SceneMap& s = scene_map();
    const Eigen::Isometry3d truth = s.path[6];
    std::vector<Eigen::Vector3f> scan = mt::view(s.scene, truth, 60.0);
    // Unmapped, ahead (LiDAR +x), far above anything the map has: 1 m apart.
    for (int x = 10; x < 40; ++x)
        for (int y = -6; y < 6; ++y)
            for (int z = 25; z < 45; ++z) scan.emplace_back(x, y, z);
    for (const double sector : {0.0, 0.5}) {
        LocaliserConfig c;
        c.edge_sector_overlap = sector;
        Localiser loc(s.map, c);
        double stamp = 100.0;
        ASSERT_TRUE(track_path_start(loc, s, &stamp));
        LocalisationUpdate u;
        u = loc.process(stamp, scan, OdometryInput{truth * mt::xy_yaw(0.15, 0.0, 0.0), 0});
        ASSERT_TRUE(u.pose_valid) << u.message;
        EXPECT_GT(u.overlap, 0.5) << u.message;
        if (sector == 0.0) {
            EXPECT_EQ(u.state, LocalisationState::kTracking) << u.message;
            EXPECT_LT(error_of(u.T_map_lidar, truth).translation, 0.05) << u.message;
        } else {
            EXPECT_EQ(u.state, LocalisationState::kOffMap) << u.message;
            EXPECT_NE(u.message.find("explained towards 0 deg"), std::string::npos) << u.message;
            EXPECT_NEAR(error_of(u.T_map_lidar, truth).translation, 0.15, 0.03) << u.message;
        }
    }
}

// A newer version of the site arrives mid-session (the split robot): a localiser on it takes the
// running one's track and tracks the next scan at once, without a global localisation; a fresh one
// (the oracle) has to search first.
TEST(Localiser, ANewVersionTakesTheTrackWithoutAGlobalLocalisation) {
    const SceneMap& s = scene_map();
    const Eigen::Isometry3d T_odom_map = mt::xy_yaw(12.0, 3.0, 31.0);
    Localiser old_map(s.map);
    double stamp = 50.0;
    ASSERT_TRUE(track_path_start(old_map, s, &stamp, T_odom_map));
    const std::shared_ptr<const LocalisationMap> next = s.map;  // the map frame stays put
    Localiser taken(next), fresh(next);
    taken.take_track(old_map);
    EXPECT_EQ(taken.state(), old_map.state());
    const Eigen::Isometry3d truth = s.path[6];
    const std::vector<Eigen::Vector3f> scan = mt::view(s.scene, truth, 60.0);
    const LocalisationUpdate u = taken.process(stamp, scan, OdometryInput{T_odom_map * truth, 0});
    EXPECT_EQ(u.state, LocalisationState::kTracking) << u.message;
    EXPECT_FALSE(u.global_ran);
    EXPECT_LT(error_of(u.T_map_lidar, truth).translation, 0.05) << u.message;
    const LocalisationUpdate f = fresh.process(stamp, scan, OdometryInput{T_odom_map * truth, 0});
    EXPECT_TRUE(f.global_ran) << "a fresh localiser searches first";
}

TEST(Localiser, RefusesAnInvalidConfigurationWithOneLine) {
    LocaliserConfig c;
    c.min_overlap = 2.0;
    try {
        Localiser l(scene_map().map, c);
        FAIL();
    } catch (const common::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("min_overlap"), std::string::npos) << e.what();
    }
}

TEST(Localisation, LoadingADamagedMapIsOneLine) {
    const std::string dir =
        (std::filesystem::temp_directory_path() / ("ltm_loc_damaged_" + std::to_string(::getpid())))
            .string();
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/manifest.txt") << "ltm_map 99\nrevision 0\n";
    try {
        load_localisation_map(dir);
        FAIL() << "a damaged map loaded";
    } catch (const common::IoError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("manifest"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(dir);
}

TEST(Localisation, ARealKittiFrameIsRelocalisedFromARandomPose) {
    const mt::KittiSnippet k = mt::load_kitti(mt::fixture_kitti00(), 3);
    ASSERT_EQ(k.scans.size(), 3u);
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (const common::PointCloud& c : k.scans) scans.push_back(c.points);
    const auto map = std::make_shared<const LocalisationMap>(make_map(scans, k.poses, 0.6, 1.73));
    GlobalLocaliser g(map);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int trial = 0; trial < 3; ++trial) {
        // Frame 1 turned by a random yaw and shifted up to 5 m: its truth moves with it.
        const Eigen::Isometry3d T_pert = mt::xy_yaw(3.5 * u(rng), 3.5 * u(rng), 180.0 * u(rng));
        const GlobalLocalisation r = g.localise(mt::transformed(scans[1], T_pert));
        ASSERT_TRUE(r.localised) << trial << ": " << r.reason;
        const Errors e = error_of(r.T_map_lidar, k.poses[1] * T_pert.inverse());
        EXPECT_LT(e.translation, 0.2) << trial << ": " << r.reason;
        EXPECT_LT(e.rotation_deg, 1.0) << trial << ": " << r.reason;
    }
}

}  // namespace
}  // namespace ltm::localisation
