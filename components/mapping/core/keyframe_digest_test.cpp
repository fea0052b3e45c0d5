#include "mapping/core/keyframe_digest.hpp"

#include <gtest/gtest.h>

#include "common/core/config_check.hpp"
#include "mapping/core/mapper.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

// A synthetic scene passed twice: keyframes 0-5 every 4 m east (local maps 0-2), then back west
// 1.5 m to the side, turned round, while the odometry drifts (keyframes 6-11, local maps 3-5):
// the second pass closes loops to the first.
struct TwoPasses {
    std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(17));
    common::PoseList truth, odom;
    std::vector<common::LocalMapData> maps;
    std::vector<common::KeyframeData> keyframes;

    TwoPasses() {
        std::vector<std::vector<Eigen::Vector3f>> points;
        for (int i = 0; i < 12; ++i) {
            truth.push_back(i < 6 ? registration::test::xy_yaw(4.0 * i, 0.0, 0.0)
                                  : registration::test::xy_yaw(20.0 - 4.0 * (i - 6), 1.5, 180.0));
            const double f = i < 6 ? 0.0 : double(i - 5) / 6.0;  // drift on the way back
            odom.push_back(registration::test::xy_yaw(0.4 * f, -0.3 * f, 1.5 * f) * truth.back());
            points.push_back(registration::test::view(scene, truth.back(), 50.0));
        }
        for (std::uint64_t m = 0; m < 6; ++m) {
            const std::vector<std::vector<Eigen::Vector3f>> scans = {points[2 * m],
                                                                     points[2 * m + 1]};
            maps.push_back(registration::test::build_local_map(m, odom[2 * m], scans,
                                                               {odom[2 * m], odom[2 * m + 1]}));
        }
        for (std::size_t i = 0; i < 12; ++i) {
            common::KeyframeData k;
            k.id = i;
            k.scan_index = i;
            k.local_map_id = i / 2;
            k.stamp = double(i);
            k.T_odom_lidar = odom[i];
            k.T_anchor_lidar = maps[i / 2].T_odom_anchor.inverse() * odom[i];
            k.points = points[i];
            keyframes.push_back(k);
        }
    }
};

MapperConfig two_pass_config() {
    MapperConfig c;
    c.loop_detection.exclude_recent_keyframes = 4;
    c.loop_detection.exclude_recent_seconds = 0.0;
    c.loop_cooldown_keyframes = 0;
    return c;
}

// Replays the passes (a local map after its two keyframes), optimising when a loop is due.
void replay(const TwoPasses& s, Mapper& mapper, KeyframeDigester* digester) {
    for (const common::KeyframeData& whole : s.keyframes) {
        KeyframeResult r;
        if (digester) {
            common::KeyframeData k = whole;
            KeyframeDescriptors d;
            digester->digest(whole.points, &d, &k.points);
            EXPECT_LT(k.points.size(), whole.points.size() / 2);  // the digest is worth it
            r = mapper.add_keyframe(k, mapper.session(), d);
        } else {
            r = mapper.add_keyframe(whole);
        }
        ASSERT_TRUE(r.added) << r.message;
        if (whole.id % 2 == 1) {
            ASSERT_TRUE(mapper.add_local_map(s.maps[whole.local_map_id]).added);
        }
        if (r.optimisation_due()) {
            ASSERT_TRUE(mapper.optimise().solved);
        }
    }
}

TEST(KeyframeDigest, AMapperGivenDigestedKeyframesMakesTheSameMap) {
    const TwoPasses s;
    const MapperConfig config = two_pass_config();
    Mapper whole(config), digested(config);
    KeyframeDigester digester(config);
    replay(s, whole, nullptr);
    replay(s, digested, &digester);
    ASSERT_GE(whole.loops().size(), 2u) << "the passes must close loops";
    ASSERT_EQ(digested.loops().size(), whole.loops().size());
    for (std::size_t i = 0; i < whole.loops().size(); ++i) {
        const LoopClosure &a = whole.loops()[i], &b = digested.loops()[i];
        EXPECT_EQ(b.query_keyframe, a.query_keyframe);
        EXPECT_EQ(b.match_keyframe, a.match_keyframe);
        EXPECT_EQ(b.inliers, a.inliers);
        EXPECT_EQ(b.descriptor_distance, a.descriptor_distance);
        EXPECT_TRUE(b.T_match_query.isApprox(a.T_match_query, 1e-12)) << "loop " << i;
    }
    for (std::uint32_t k = 0; k < whole.keyframes().size(); ++k) {
        EXPECT_TRUE(digested.keyframe_pose(k).isApprox(whole.keyframe_pose(k), 1e-12)) << k;
        const map::StoredKeyframe &a = *whole.keyframes()[k], &b = *digested.keyframes()[k];
        EXPECT_EQ(b.descriptor.value, a.descriptor.value);
        EXPECT_EQ(b.localisation_descriptor.value, a.localisation_descriptor.value);
        EXPECT_EQ(b.localisation_descriptor.spread, a.localisation_descriptor.spread);
    }
}

TEST(KeyframeDigest, DescriptorsMadeOtherwiseAreMadeAgainFromThePoints) {
    const TwoPasses s;
    MapperConfig robot = two_pass_config();
    robot.scan_context.sensor_height = 1.73;  // the robot's digest set up unlike the mapping
    robot.localisation_descriptor.rings = 10;
    KeyframeDigester digester(robot);
    KeyframeDescriptors given;
    std::vector<Eigen::Vector3f> sampled;
    digester.digest(s.keyframes[0].points, &given, &sampled);
    const MapperConfig config = two_pass_config();
    EXPECT_FALSE(usable(given.loop, config.scan_context));
    EXPECT_FALSE(usable(given.localisation, config.localisation_descriptor));
    Mapper mapper(config);
    common::KeyframeData k = s.keyframes[0];
    k.points = sampled;
    ASSERT_TRUE(mapper.add_keyframe(k, mapper.session(), given).added);
    const map::StoredKeyframe& stored = *mapper.keyframes()[0];
    EXPECT_EQ(stored.descriptor.value,
              places::make_scan_context(sampled, config.scan_context).value);
    EXPECT_EQ(stored.localisation_descriptor.rings, config.localisation_descriptor.rings);
}

TEST(KeyframeDigest, OnlyADescriptorOfTheStatedShapeIsUsable) {
    const places::ScanContextConfig c = MapperConfig().localisation_descriptor;  // ScanContext++
    const std::vector<Eigen::Vector3f> points = registration::test::view(
        registration::test::synthetic_scene(3), Eigen::Isometry3d::Identity(), 40.0);
    const MadeDescriptor good{places::make_scan_context(points, c), c};
    EXPECT_EQ(usable(good, c), &good.descriptor);
    EXPECT_FALSE(usable(MadeDescriptor{}, c));  // none given
    MadeDescriptor bad = good;
    bad.descriptor.spread.pop_back();
    EXPECT_FALSE(usable(bad, c));
    bad = good;
    bad.descriptor.occupied.clear();
    EXPECT_FALSE(usable(bad, c));
    bad = good;
    bad.made_with.max_range += 1.0;
    EXPECT_FALSE(usable(bad, c));
    // The comparison settings do not make the descriptor.
    places::ScanContextConfig other = c;
    other.empty_bin_cost = 9.0;
    other.shift_search_radius = 3;
    EXPECT_TRUE(usable(good, other));
}

TEST(KeyframeDigest, AnInvalidConfigurationIsRefusedNamingTheKey) {
    MapperConfig c;
    c.verification.max_points = 0;
    try {
        KeyframeDigester digester(c);
        FAIL() << "accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("max_points"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace ltm::mapping
