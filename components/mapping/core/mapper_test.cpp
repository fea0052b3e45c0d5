#include "mapping/core/mapper.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "map/core/map_store.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

constexpr double kDeg = M_PI / 180.0;

double angle_deg(const Eigen::Isometry3d& T) {
    return Eigen::AngleAxisd(T.linear()).angle() / kDeg;
}

// KITTI 00 frames 0-15 driven forward (two local maps of 8 keyframes), then in reverse with the
// sensor turned round (the other half of the points; four local maps of 4 keyframes) while the
// odometry drifts, map by map, up to `drift` at the end.
struct ForwardReverse {
    registration::test::KittiSnippet kitti;
    Eigen::Isometry3d drift = registration::test::xy_yaw(1.2, -0.8, 4.0);
    Eigen::Isometry3d turn = registration::test::xy_yaw(0, 0, 180.0);
    // Per keyframe: true world pose, odometry pose, local map id, points.
    common::PoseList truth, odom;
    std::vector<std::uint64_t> map_of;
    std::vector<std::vector<Eigen::Vector3f>> points;
    std::vector<common::LocalMapData> maps;

    explicit ForwardReverse(const std::string& dir)
        : kitti(registration::test::load_kitti(dir, 16)) {
        for (int pass = 0; pass < 2; ++pass) {
            for (int j = 0; j < 16; ++j) {
                const int f = pass == 0 ? j : 15 - j;
                const Eigen::Isometry3d T = pass == 0 ? kitti.poses[f] : kitti.poses[f] * turn;
                const std::uint64_t map =
                    pass == 0 ? std::uint64_t(j / 8) : std::uint64_t(2 + j / 4);
                truth.push_back(T);
                odom.push_back(pass == 0 ? T : drift_of(map) * T);
                map_of.push_back(map);
                const std::vector<Eigen::Vector3f> half =
                    registration::test::every_nth(kitti.scans[f].points, 2, pass);
                points.push_back(pass == 0 ? half
                                           : registration::test::transformed(half, turn.inverse()));
            }
        }
        for (std::uint64_t m = 0; m < 6; ++m) {
            std::vector<std::vector<Eigen::Vector3f>> scans;
            common::PoseList poses;
            for (std::size_t i = 0; i < truth.size(); ++i) {
                if (map_of[i] != m) continue;
                scans.push_back(points[i]);
                poses.push_back(odom[i]);
            }
            maps.push_back(registration::test::build_local_map(m, poses.front(), scans, poses));
        }
    }

    // A quarter of the drift more with every local map of the way back.
    Eigen::Isometry3d drift_of(std::uint64_t map) const {
        if (map < 2) return Eigen::Isometry3d::Identity();
        const double f = double(map - 1) / 4.0;
        const Eigen::Vector3d t = drift.translation() * f;
        const double yaw = Eigen::AngleAxisd(drift.linear()).angle() / kDeg * f;
        return registration::test::xy_yaw(t.x(), t.y(), yaw);
    }

    common::KeyframeData keyframe(std::size_t i) const {
        common::KeyframeData k;
        k.id = i;
        k.scan_index = i;
        k.local_map_id = map_of[i];
        k.stamp = 0.1 * double(i);
        k.T_odom_lidar = odom[i];
        k.T_anchor_lidar = maps[map_of[i]].T_odom_anchor.inverse() * odom[i];
        k.points = points[i];
        return k;
    }
};

MapperConfig kitti_config() {
    MapperConfig c;
    c.scan_context.sensor_height = 1.73;
    c.loop_detection.exclude_recent_keyframes = 6;
    c.loop_detection.exclude_recent_seconds = 0.0;
    c.loop_cooldown_keyframes = 1;
    // This odometry drifts by 4 deg over 11 m: its edges are weighted accordingly.
    c.odometry_edge.sigma_translation_per_m = 0.05;
    c.odometry_edge.sigma_rotation_per_m = 0.1;
    return c;
}

// Replays the snippet: each local map arrives when the odometry would finish it (after its last
// keyframe); the last one at the end.
std::vector<KeyframeResult> replay(const ForwardReverse& s, Mapper& mapper) {
    std::vector<KeyframeResult> out;
    for (std::size_t i = 0; i < s.truth.size(); ++i) {
        out.push_back(mapper.add_keyframe(s.keyframe(i)));
        EXPECT_TRUE(out.back().added) << out.back().message;
        if (i + 1 == s.truth.size() || s.map_of[i + 1] != s.map_of[i]) {
            const LocalMapResult m = mapper.add_local_map(s.maps[s.map_of[i]]);
            EXPECT_TRUE(m.added) << m.message;
        }
    }
    return out;
}

TEST(Mapper, ClosesLoopsOnARealKittiSnippetReplayedInReverse) {
    const std::string dir = registration::test::shared_kitti00();
    if (dir.empty()) GTEST_SKIP() << "KITTI 00 frames 0-15 not found under ../shared/data/kitti";
    const ForwardReverse s(dir);
    Mapper mapper(kitti_config());
    const std::vector<KeyframeResult> results = replay(s, mapper);

    // Loops, each with the true relative pose (no false loop); most on the way back.
    std::size_t back = 0;
    for (const LoopClosure& l : mapper.loops()) {
        const Eigen::Isometry3d truth = s.truth[l.match_scan].inverse() * s.truth[l.query_scan];
        const Eigen::Isometry3d err = truth.inverse() * l.T_match_query;
        EXPECT_LT(err.translation().norm(), 0.1)
            << "loop " << l.query_scan << " -> " << l.match_scan;
        EXPECT_LT(angle_deg(err), 0.5) << "loop " << l.query_scan << " -> " << l.match_scan;
        // The descriptor's yaw is the true one to within two sectors.
        const double yaw = std::atan2(truth.linear()(1, 0), truth.linear()(0, 0));
        EXPECT_LT(std::abs(std::remainder(l.descriptor_yaw - yaw, 2 * M_PI)) / kDeg, 12.0);
        if (l.query_scan >= 16 && l.match_scan < 16) ++back;
    }
    EXPECT_GE(back, 5u);  // the way back meets the way out again and again
    // At most max_loops_per_anchor_pair loop edges join two local maps.
    std::map<std::pair<std::uint64_t, std::uint64_t>, int> per_pair;
    for (const LoopClosure& l : mapper.loops())
        ++per_pair[{std::min(l.from_node, l.to_node), std::max(l.from_node, l.to_node)}];
    for (const auto& [pair, n] : per_pair) EXPECT_LE(n, kitti_config().max_loops_per_anchor_pair);

    // Before optimisation the way back is off by the drift; after it, on the truth.
    auto worst = [&]() {
        double w = 0.0;
        for (std::uint32_t i = 16; i < 32; ++i) {
            w = std::max(w,
                         (mapper.keyframe_pose(i).translation() - s.truth[i].translation()).norm());
        }
        return w;
    };
    EXPECT_GT(worst(), 1.0);
    const OptimisationSummary r = mapper.optimise();
    ASSERT_TRUE(r.solved) << r.message;
    EXPECT_EQ(r.loops_rejected, 0u);
    EXPECT_EQ(mapper.revision(), 1u);
    EXPECT_LT(worst(), 0.1);
    // The corrected odometry frame of the way back undoes the drift.
    const Eigen::Isometry3d c = *mapper.T_world_odom(5) * s.drift;
    EXPECT_LT(c.translation().norm(), 0.1);
    EXPECT_LT(angle_deg(c), 0.5);
    // The global map: the six local maps fused.
    map::GlobalMapStats stats;
    const common::PlyCloud cloud = mapper.global_map(&stats);
    EXPECT_GT(cloud.points.size(), 1000u);
    EXPECT_LT(stats.fused_voxels, stats.input_voxels);
}

TEST(Mapper, OptimisingASnapshotElsewhereGivesTheSameResult) {
    const std::string dir = registration::test::shared_kitti00();
    if (dir.empty()) GTEST_SKIP() << "KITTI 00 frames 0-15 not found under ../shared/data/kitti";
    const ForwardReverse s(dir);
    Mapper a(kitti_config()), b(kitti_config());
    replay(s, a);
    replay(s, b);
    a.optimise();
    PoseGraph snapshot = b.graph_snapshot();
    const OptimisationSummary r = snapshot.optimise();
    // Meanwhile b goes on: a node is added after the snapshot.
    common::KeyframeData extra = s.keyframe(31);
    extra.local_map_id = 6;
    extra.T_anchor_lidar = Eigen::Isometry3d::Identity();
    ASSERT_TRUE(b.add_keyframe(extra).added);
    ASSERT_TRUE(b.apply(snapshot, r));
    for (const map::PoseGraphNode& n : a.graph().nodes()) {
        const Eigen::Isometry3d d =
            n.T_world_anchor.inverse() * b.graph().find(n.id)->T_world_anchor;
        EXPECT_LT(d.translation().norm(), 1e-9);
    }
    // The new node follows the correction of its predecessor.
    const Eigen::Isometry3d corrected = *b.T_world_lidar(6, extra.T_odom_lidar);
    EXPECT_LT((corrected.translation() - s.truth[31].translation()).norm(), 0.1);
}

TEST(Mapper, SavedMapReloadsAndANewSessionClosesALoopAgainstIt) {
    const std::string dir = registration::test::shared_kitti00();
    if (dir.empty()) GTEST_SKIP() << "KITTI 00 frames 0-15 not found under ../shared/data/kitti";
    const ForwardReverse s(dir);
    Mapper mapper(kitti_config());
    replay(s, mapper);
    mapper.optimise();
    const std::string path = std::string(LTM_BINARY_DIR) + "/mapping_test_maps/mapper_session";
    std::filesystem::remove_all(path);
    map::save_map(path, mapper.snapshot());
    const map::LoadedMap loaded = map::load_map(path);
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused[0];
    EXPECT_EQ(loaded.map.local_maps.size(), 6u);
    EXPECT_EQ(loaded.map.keyframes.size(), 32u);

    // A later run, its own odometry frame: frame 6 seen while turned by 90 degrees.
    Mapper next(kitti_config(), loaded.map);
    EXPECT_EQ(next.session(), 1u);
    const Eigen::Isometry3d turn = registration::test::xy_yaw(0, 0, 90.0);
    common::KeyframeData k;
    k.id = 0;
    k.local_map_id = 0;
    k.T_odom_lidar = Eigen::Isometry3d::Identity();
    k.T_anchor_lidar = Eigen::Isometry3d::Identity();
    k.points = registration::test::transformed(s.kitti.scans[6].points, turn.inverse());
    const KeyframeResult r = next.add_keyframe(k);
    ASSERT_EQ(r.loops.size(), 1u) << (r.rejected.empty() ? "no candidate" : r.rejected[0].reason);
    EXPECT_EQ(r.loops[0].match_session, 0u);
    ASSERT_TRUE(next.optimise().solved);
    // The new session's anchor lands where frame 6 really was (the old map is held fixed).
    const Eigen::Isometry3d err = (s.kitti.poses[6] * turn).inverse() * next.keyframe_pose(32);
    EXPECT_LT(err.translation().norm(), 0.1);
    EXPECT_LT(angle_deg(err), 0.5);
}

// A revisit a few metres beside the first pass, facing the other way: the descriptor's guess (the
// matched keyframe's place) is 6 m from the truth, beyond the verifier's reach; the graph's
// estimate (odometry 0.3 m off) is within it.
TEST(Mapper, ARevisitBesideTheFirstPassIsVerifiedFromTheGraphsEstimate) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(44));
    const Eigen::Isometry3d first = registration::test::xy_yaw(0, 0, 0),
                            again = registration::test::xy_yaw(1.0, 6.0, 180.0);
    const Eigen::Isometry3d drift =
        registration::test::xy_yaw(0.3, -0.2, 1.0);  // odometry error at `again`
    MapperConfig config;
    config.loop_detection.exclude_recent_keyframes = 0;
    config.loop_detection.exclude_recent_seconds = 0.0;
    config.loop_detection.max_distance = 0.9;  // the views differ: any candidate will do
    config.verification.max_correction_translation = 3.0;
    config.odometry_edge.sigma_translation = 1.0;  // loop edge far more certain
    config.odometry_edge.sigma_rotation = 5.0;
    auto keyframe = [&](std::uint64_t id, const Eigen::Isometry3d& T_true,
                        const Eigen::Isometry3d& T_odom) {
        common::KeyframeData k;
        k.id = id;
        k.scan_index = id;
        k.local_map_id = id;
        k.stamp = double(id);
        k.T_odom_lidar = T_odom;
        k.T_anchor_lidar = Eigen::Isometry3d::Identity();
        k.points = registration::test::view(scene, T_true, 50.0);
        return k;
    };
    for (const bool from_graph : {false, true}) {
        config.verify_from_graph = from_graph;
        Mapper mapper(config);
        const common::KeyframeData k0 = keyframe(0, first, first);
        ASSERT_TRUE(mapper.add_keyframe(k0).added);
        ASSERT_TRUE(
            mapper
                .add_local_map(registration::test::build_local_map(0, first, {k0.points}, {first}))
                .added);
        const KeyframeResult r = mapper.add_keyframe(keyframe(1, again, drift * again));
        ASSERT_TRUE(r.added) << r.message;
        ASSERT_GE(r.candidates, 1u);
        if (!from_graph) {
            EXPECT_TRUE(r.loops.empty()) << "closed from the descriptor's guess";
            ASSERT_FALSE(r.rejected.empty());
            continue;
        }
        ASSERT_EQ(r.loops.size(), 1u) << (r.rejected.empty() ? "" : r.rejected[0].reason);
        const LoopClosure& l = r.loops[0];
        EXPECT_TRUE(l.from_graph_guess);
        const Eigen::Isometry3d err = (first.inverse() * again).inverse() * l.T_match_query;
        EXPECT_LT(err.translation().norm(), 0.05);
        EXPECT_LT(angle_deg(err), 0.2);
        // The loop edge moves the keyframe to the truth.
        EXPECT_GT((mapper.keyframe_pose(1).translation() - again.translation()).norm(), 0.2);
        ASSERT_TRUE(mapper.optimise().solved);
        EXPECT_LT((mapper.keyframe_pose(1).translation() - again.translation()).norm(), 0.05);
    }
}

TEST(Mapper, BadInputIsRefusedWithAReason) {
    Mapper mapper{MapperConfig()};
    common::KeyframeData k;
    k.T_odom_lidar.translation().x() = std::nan("");
    const KeyframeResult r = mapper.add_keyframe(k);
    EXPECT_FALSE(r.added);
    EXPECT_NE(r.message.find("not a finite rigid transform"), std::string::npos);
    common::LocalMapData m;
    m.voxel_size = 0.0f;
    EXPECT_FALSE(mapper.add_local_map(m).added);
    m.voxel_size = 1.0f;
    m.revision = 3;
    EXPECT_TRUE(mapper.add_local_map(m).added);
    m.revision = 2;
    const LocalMapResult older = mapper.add_local_map(m);
    EXPECT_FALSE(older.added);
    EXPECT_NE(older.message.find("older"), std::string::npos);
    MapperConfig bad;
    bad.odometry_edge.sigma_rotation = 0.0;
    try {
        Mapper m2(bad);
        FAIL();
    } catch (const common::ConfigError& e) {
        EXPECT_STREQ(e.what(), "mapping.odometry_edge.sigma_rotation: must be > 0 (got 0)");
    }
}

common::KeyframeData scene_keyframe(std::uint64_t id, const Eigen::Isometry3d& T) {
    static const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(4, 30.0);
    common::KeyframeData k;
    k.id = id;
    k.scan_index = id;
    k.local_map_id = id;
    k.stamp = double(id);
    k.T_odom_lidar = T;
    k.T_anchor_lidar = Eigen::Isometry3d::Identity();
    k.points = registration::test::view(scene, T, 30.0);
    return k;
}

TEST(Mapper, KeyframesCarryALocalisationDescriptorIntoTheSnapshot) {
    MapperConfig config = mapper_preset(common::SensorPreset::kNarrow);
    EXPECT_EQ(config.localisation_descriptor.kind, places::ScanContextKind::kMeanVariance);
    EXPECT_EQ(config.localisation_descriptor.rings, 20);
    EXPECT_EQ(config.localisation_descriptor.sectors, 60);
    EXPECT_EQ(config.localisation_descriptor.max_range, 40.0);  // the preset's scan_context's
    EXPECT_EQ(config.localisation_descriptor.sensor_height, 1.0);
    Mapper mapper(config);
    const std::size_t before = mapper.memory_bytes();
    const common::KeyframeData k = scene_keyframe(0, registration::test::xy_yaw(1, 2, 30));
    ASSERT_TRUE(mapper.add_keyframe(k).added);
    const map::MapData m = mapper.snapshot();
    EXPECT_EQ(m.localisation_descriptor_config.rings, 20);
    EXPECT_EQ(m.localisation_descriptor_config.max_range, 40.0);
    const places::ScanContext expected =
        places::make_scan_context(k.points, config.localisation_descriptor);
    const places::ScanContext& got = m.keyframes[0]->localisation_descriptor;
    EXPECT_EQ(got.kind, places::ScanContextKind::kMeanVariance);
    EXPECT_EQ(got.value, expected.value);
    EXPECT_EQ(got.spread, expected.spread);
    EXPECT_EQ(got.occupied, expected.occupied);
    EXPECT_GT(std::count(got.occupied.begin(), got.occupied.end(), 1), 50);
    // The loop descriptor is unchanged.
    EXPECT_EQ(m.keyframes[0]->descriptor.value,
              places::make_scan_context(k.points, config.scan_context).value);
    // Both descriptors are counted: 1200 bins of mean, spread and occupancy (9 bytes), 1200 of
    // max height and occupancy (5 bytes).
    EXPECT_GE(mapper.memory_bytes() - before, 1200u * 9 + 1200u * 5);
}

TEST(Mapper, WithoutLoopClosureAKeyframeIsOnlyStored) {
    for (const bool loop_closure : {true, false}) {
        MapperConfig config;
        config.loop_detection.exclude_recent_keyframes = 0;
        config.loop_detection.exclude_recent_seconds = 0.0;
        config.loop_closure = loop_closure;
        Mapper mapper(config);
        ASSERT_TRUE(
            mapper.add_keyframe(scene_keyframe(0, registration::test::xy_yaw(0, 0, 0))).added);
        // The same place again, in another local map: a loop candidate when loops are closed.
        const KeyframeResult r =
            mapper.add_keyframe(scene_keyframe(1, registration::test::xy_yaw(0.2, 0, 5)));
        ASSERT_TRUE(r.added) << r.message;
        if (loop_closure) {
            EXPECT_GE(r.candidates, 1u);
        } else {
            EXPECT_EQ(r.candidates, 0u);
            EXPECT_FALSE(r.verified);
        }
        ASSERT_EQ(mapper.keyframes().size(), 2u);
        EXPECT_FALSE(mapper.keyframes()[1]->descriptor.empty());
        EXPECT_FALSE(mapper.keyframes()[1]->localisation_descriptor.empty());
    }
}

TEST(Mapper, AFormat1MapIsContinuedWithLocalisationDescriptorsOnTheNewKeyframes) {
    const MapperConfig config;
    Mapper first(config);
    ASSERT_TRUE(first.add_keyframe(scene_keyframe(0, registration::test::xy_yaw(0, 0, 0))).added);
    map::MapData v1 = first.snapshot();  // as a format-1 map loads: no localisation descriptors
    v1.localisation_descriptor_config = map::no_localisation_descriptors();
    auto old = std::make_shared<map::StoredKeyframe>(*v1.keyframes[0]);
    old->localisation_descriptor = places::ScanContext();
    v1.keyframes[0] = old;
    Mapper next(config, v1);
    ASSERT_TRUE(next.add_keyframe(scene_keyframe(0, registration::test::xy_yaw(5, 0, 10))).added);
    const map::MapData m = next.snapshot();
    ASSERT_EQ(m.keyframes.size(), 2u);
    EXPECT_TRUE(m.keyframes[0]->localisation_descriptor.empty());
    EXPECT_FALSE(m.keyframes[1]->localisation_descriptor.empty());
    EXPECT_TRUE(map::has_localisation_descriptors(m.localisation_descriptor_config));
    // Saved in format 2 (the old keyframe's descriptor empty) and loaded again.
    const std::string path = std::string(LTM_BINARY_DIR) + "/mapping_test_maps/continued_v1";
    std::filesystem::remove_all(path);
    map::save_map(path, m);
    const map::LoadedMap loaded = map::load_map(path);
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused[0];
    ASSERT_EQ(loaded.map.keyframes.size(), 2u);
    EXPECT_TRUE(loaded.map.keyframes[0]->localisation_descriptor.empty());
    EXPECT_EQ(loaded.map.keyframes[1]->localisation_descriptor.value,
              m.keyframes[1]->localisation_descriptor.value);
    // A format-2 map continues only with the same localisation descriptor settings.
    EXPECT_NO_THROW(Mapper(config, loaded.map));
    MapperConfig other = config;
    other.localisation_descriptor.sectors = 72;
    try {
        Mapper m2(other, loaded.map);
        ADD_FAILURE() << "localisation descriptors of another shape accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_EQ(e.key(), "mapping.localisation_descriptor");
        EXPECT_EQ(e.problem().rfind("differs from the loaded map's descriptors (20 x 60", 0), 0u)
            << e.problem();
    }
    other = config;
    other.localisation_descriptor.max_range = 50.0;
    EXPECT_THROW(Mapper(other, loaded.map), common::ConfigError);
    other = config;
    other.localisation_descriptor.kind = places::ScanContextKind::kMaxHeight;
    try {
        Mapper m3(other);
        ADD_FAILURE() << "a Scan Context localisation descriptor accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_STREQ(e.what(),
                     "mapping.localisation_descriptor.kind: must be mean_variance (ScanContext++)");
    }
}

TEST(Mapper, LoadedMapThatDoesNotFitIsRefusedNamingTheKey) {
    map::MapData loaded;
    loaded.descriptor_config.rings = 24;  // the config keeps 20
    try {
        Mapper m(MapperConfig(), loaded);
        ADD_FAILURE() << "descriptors of another shape accepted";
    } catch (const common::ConfigError& e) {
        EXPECT_EQ(e.key(), "mapping.scan_context");
        EXPECT_EQ(e.problem().rfind("differs from the loaded map's descriptors (24 x 60", 0), 0u)
            << e.problem();
    }
    loaded.descriptor_config = MapperConfig().scan_context;
    map::PoseGraphNode node;
    node.id = 3;
    loaded.nodes = {node, node};  // repeated
    try {
        Mapper m(MapperConfig(), loaded);
        ADD_FAILURE() << "a repeated node accepted";
    } catch (const common::IoError& e) {
        EXPECT_STREQ(e.what(), "loaded map: node 3 is invalid or repeated");
    }
}

}  // namespace
}  // namespace ltm::mapping
