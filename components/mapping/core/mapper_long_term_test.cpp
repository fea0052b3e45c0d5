// The Mapper on one map over sessions (LongTermConfig): a second session over a mapped site
// updates the existing local maps instead of adding its own, stores no keyframe where one is
// stored already, and loops that agree with the graph make no optimisation due.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>

#include "mapping/core/map_fix_pairer.hpp"
#include "mapping/core/mapper.hpp"
#include "mapping/core/mapper_test_drive.hpp"
#include "mapping/core/removed_cells.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

using test::Drive;
using test::replay;
using test::test_config;

TEST(MapperLongTerm, ASecondSessionOverAMappedSiteAddsNoLocalMapWhereItDrivesOverMappedPlaces) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    const MapperConfig config = test_config();
    Mapper first(config);
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), first);
    ASSERT_TRUE(first.optimise().solved);
    ASSERT_EQ(first.local_map_count(), 4u);
    const map::MapData map = first.snapshot();
    std::size_t voxels_before = 0;
    for (const map::StoredLocalMap& m : map.local_maps) voxels_before += m.data->voxels.size();

    // A day later, the same road 0.5 m further on and 0.3 m aside, in another odometry frame;
    // from keyframe 8 on, the odometry is off by 0.4 m more.
    const Eigen::Isometry3d T_odom_world = registration::test::xy_yaw(-20.0, 7.0, 35.0);
    const Drive again(scene, 0.5, 0.3, T_odom_world, 86400.0, 8,
                      registration::test::xy_yaw(0.4, -0.2, 0.5));
    Mapper next(config, map);
    ASSERT_EQ(next.session(), 1u);
    std::vector<LocalMapResult> results;
    const std::vector<KeyframeResult> kf = replay(again, next, &results);

    // Every local map of the second session went into a map of the first.
    ASSERT_EQ(results.size(), 4u);
    std::set<std::uint64_t> into;
    for (const LocalMapResult& r : results) {
        EXPECT_TRUE(r.merged) << "node " << r.node;
        into.insert(r.node);
        const map::PoseGraphNode* n = next.graph().find(r.node);
        ASSERT_NE(n, nullptr);
        EXPECT_EQ(n->session, 0u);
    }
    EXPECT_EQ(next.local_map_count(), 4u);
    EXPECT_EQ(next.graph().nodes().size(), 4u);
    for (const map::PoseGraphEdge& e : next.graph().edges()) {
        EXPECT_NE(next.graph().find(e.from), nullptr);
        EXPECT_NE(next.graph().find(e.to), nullptr);
    }
    // The updated maps hold the new observations and a higher revision; the voxels barely grow
    // (the same surfaces), the stamps of both sessions are in them.
    const map::MapData after = next.snapshot();
    std::size_t voxels_after = 0;
    for (const map::StoredLocalMap& m : after.local_maps) {
        voxels_after += m.data->voxels.size();
        if (into.count(m.node)) {
            EXPECT_GT(m.data->revision, 1u);
            EXPECT_GE(m.data->observation_times.back(), 86400.0);
        }
    }
    EXPECT_LT(double(voxels_after), 1.15 * double(voxels_before));
    // Keyframes within 1 m of a stored one are not stored again.
    std::size_t kept = 0;
    for (const KeyframeResult& r : kf) kept += r.kept;
    EXPECT_LT(kept, 4u);
    EXPECT_EQ(next.keyframes().size(), 16u + kept);
    // Every keyframe names a node of the graph, at its true place.
    for (std::uint32_t i = 0; i < next.keyframes().size(); ++i) {
        ASSERT_NE(next.graph().find(next.keyframes()[i]->node), nullptr);
    }
    // The second session's poses, through the maps it folded, are where it really was.
    for (std::size_t i = 0; i < 16; ++i) {
        const std::optional<Eigen::Isometry3d> T = next.T_world_lidar(i / 4, again.odom[i]);
        ASSERT_TRUE(T);
        EXPECT_LT((T->translation() - again.truth[i].translation()).norm(), 0.15)
            << "keyframe " << i;
    }
    // The sessions that built the map.
    const std::vector<map::SessionRecord> sessions = next.sessions();
    ASSERT_EQ(sessions.size(), 2u);
    EXPECT_EQ(sessions[0].id, 0u);
    EXPECT_EQ(sessions[0].local_maps_added, 4u);
    EXPECT_EQ(sessions[1].id, 1u);
    EXPECT_EQ(sessions[1].local_maps_added, 0u);
    EXPECT_EQ(sessions[1].local_maps_updated, into.size());
    EXPECT_EQ(sessions[1].first_stamp, 86400.0);
    EXPECT_EQ(sessions[1].last_stamp, 86415.0);
}

// A fold registers the folded map's surfaces to the map they go into (register_fold): the
// second session's four local maps are each registered, the corrections to the graph's estimate
// small (the loops placed them well); with register_fold off none is tried and the folds are the
// graph's.
TEST(MapperLongTerm, AFoldRegistersTheFoldedMapToTheOneItGoesInto) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    const MapperConfig config = test_config();
    Mapper first(config);
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), first);
    ASSERT_TRUE(first.optimise().solved);
    const map::MapData map = first.snapshot();
    const Drive again(scene, 0.5, 0.3, registration::test::xy_yaw(-20.0, 7.0, 35.0), 86400.0);

    Mapper registered(config, map);
    std::vector<LocalMapResult> results;
    replay(again, registered, &results);
    std::size_t merged = 0;
    for (const LocalMapResult& r : results) merged += r.merged;
    ASSERT_GE(merged, 3u);
    const Mapper::FoldStats& f = registered.fold_stats();
    EXPECT_EQ(f.tried, merged);
    EXPECT_EQ(f.registered, merged);
    ASSERT_EQ(f.corrections.size(), merged);
    for (const double c : f.corrections) EXPECT_LT(c, 0.1);

    MapperConfig off = config;
    off.long_term.register_fold = false;
    Mapper by_graph(off, map);
    results.clear();
    replay(again, by_graph, &results);
    merged = 0;
    for (const LocalMapResult& r : results) merged += r.merged;
    EXPECT_GE(merged, 3u);
    EXPECT_EQ(by_graph.fold_stats().tried, 0u);
}

// The road driven the other way a day later (a 360 deg sensor): with a spinning sensor's preset
// (keyframe_angle 180) a stored keyframe stands for a revisit whatever its heading, so the
// reversed drive stores (almost) no keyframe; with 15 deg it stored a second set (issue 26).
TEST(MapperLongTerm, ARoadDrivenTheOtherWayStoresNoSecondSetOfKeyframesForASpinningSensor) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    EXPECT_EQ(mapper_preset(common::SensorPreset::kVlp32).long_term.keyframe_angle, 180.0);
    EXPECT_EQ(mapper_preset(common::SensorPreset::kNarrow).long_term.keyframe_angle, 15.0);
    std::size_t kept_at[2] = {0, 0};
    for (const double angle : {15.0, 180.0}) {
        MapperConfig config = test_config();
        config.long_term.keyframe_angle = angle;
        Mapper first(config);
        replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), first);
        ASSERT_TRUE(first.optimise().solved);
        // Westwards from the far end, 0.3 m aside, in another odometry frame.
        const Drive back(scene, 45.2, 0.3, registration::test::xy_yaw(-20.0, 7.0, 35.0), 86400.0,
                         1000, Eigen::Isometry3d::Identity(), 0, true);
        Mapper next(config, first.snapshot());
        std::vector<LocalMapResult> results;
        const std::vector<KeyframeResult> kf = replay(back, next, &results);
        std::size_t kept = 0, looped = 0;
        for (const KeyframeResult& r : kf) {
            kept += r.kept;
            looped += !r.loops.empty();
        }
        EXPECT_GT(looped, 2u) << "angle " << angle;  // the loops are still found both ways
        EXPECT_EQ(next.keyframes().size(), 16u + kept);
        kept_at[angle > 90.0] = kept;
        // The second session's poses are where it really was.
        for (std::size_t i = 0; i < 16; ++i) {
            const std::optional<Eigen::Isometry3d> T = next.T_world_lidar(i / 4, back.odom[i]);
            ASSERT_TRUE(T);
            EXPECT_LT((T->translation() - back.truth[i].translation()).norm(), 0.15)
                << "keyframe " << i << ", angle " << angle;
        }
    }
    EXPECT_GT(kept_at[0], 10u);  // 15 deg: a second set
    EXPECT_LT(kept_at[1], 4u);   // 180 deg: the first day's keyframes stand for them
}

// Laps of one session: the second lap over the road folds its maps into the first lap's, and the
// chain of odometry edges goes on through the maps they went into.
TEST(MapperLongTerm, ASecondLapOfOneSessionUpdatesTheFirstLapsMaps) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    Mapper mapper(test_config());
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), mapper);
    // Back at the start 100 s later (the way back is not mapped here), 0.3 m aside, the odometry
    // 0.3 m and 1 deg off by then.
    const Drive lap2(scene, 0.5, 0.3, registration::test::xy_yaw(0.3, -0.2, 1.0), 100.0, 1000,
                     Eigen::Isometry3d::Identity(), 4);
    std::vector<LocalMapResult> results;
    replay(lap2, mapper, &results);
    ASSERT_EQ(results.size(), 4u);
    for (const LocalMapResult& r : results) {
        EXPECT_TRUE(r.merged);
        EXPECT_LT(r.node, 4u);  // a node of the first lap
    }
    EXPECT_EQ(mapper.local_map_count(), 4u);
    EXPECT_EQ(mapper.graph().nodes().size(), 4u);
    // The first lap's three odometry edges and the one back from its last map to its first (the
    // way back, a new pair of places); no second copy of the first lap's.
    std::size_t odometry = 0;
    for (const map::PoseGraphEdge& e : mapper.graph().edges())
        odometry += e.kind == map::EdgeKind::kOdometry;
    EXPECT_EQ(odometry, 4u);
    for (std::size_t i = 0; i < 16; ++i) {
        const std::optional<Eigen::Isometry3d> T = mapper.T_world_lidar(4 + i / 4, lap2.odom[i]);
        ASSERT_TRUE(T);
        EXPECT_LT((T->translation() - lap2.truth[i].translation()).norm(), 0.15)
            << "keyframe " << i;
    }
    const std::vector<map::SessionRecord> sessions = mapper.sessions();
    ASSERT_EQ(sessions.size(), 1u);
    EXPECT_EQ(sessions[0].local_maps_added, 4u);
    EXPECT_EQ(sessions[0].local_maps_updated, 0u);  // its own maps: added, not updated
}

// A fold between two laps of one session is placed by the graph, registered or not: both maps
// are the same optimisation's, whose estimate is the loops' (the registration of the voxels
// overrode it: site_loop day 0's final keyframes 0.065 -> 0.087 m rmse). The map, its keyframes
// and the graph are those of register_fold off; a fold into an earlier session's map is still
// registered (AFoldRegistersTheFoldedMapToTheOneItGoesInto).
TEST(MapperLongTerm, AFoldBetweenLapsOfOneSessionIsPlacedByTheGraph) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    // The second lap 0.3 m aside, its odometry 0.3 m and 1 deg off by then (as in
    // ASecondLapOfOneSessionUpdatesTheFirstLapsMaps).
    const Drive lap1(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0);
    const Drive lap2(scene, 0.5, 0.3, registration::test::xy_yaw(0.3, -0.2, 1.0), 100.0, 1000,
                     Eigen::Isometry3d::Identity(), 4);
    MapperConfig config = test_config();
    ASSERT_TRUE(config.long_term.register_fold);
    Mapper mapper(config);
    replay(lap1, mapper);
    std::vector<LocalMapResult> results;
    replay(lap2, mapper, &results);
    std::size_t merged = 0;
    for (const LocalMapResult& r : results) merged += r.merged;
    ASSERT_GE(merged, 3u);
    EXPECT_EQ(mapper.fold_stats().tried, 0u);
    EXPECT_EQ(mapper.fold_stats().registered, 0u);

    config.long_term.register_fold = false;
    Mapper by_graph(config);
    replay(lap1, by_graph);
    replay(lap2, by_graph);
    ASSERT_EQ(mapper.keyframes().size(), by_graph.keyframes().size());
    for (std::size_t i = 0; i < mapper.keyframes().size(); ++i) {
        const map::StoredKeyframe& a = *mapper.keyframes()[i];
        const map::StoredKeyframe& b = *by_graph.keyframes()[i];
        EXPECT_EQ(a.node, b.node) << "keyframe " << i;
        EXPECT_TRUE(a.data.T_anchor_lidar.isApprox(b.data.T_anchor_lidar, 1e-12))
            << "keyframe " << i;
    }
    for (std::size_t i = 0; i < 16; ++i) {
        const std::optional<Eigen::Isometry3d> T = mapper.T_world_lidar(4 + i / 4, lap2.odom[i]);
        const std::optional<Eigen::Isometry3d> U = by_graph.T_world_lidar(4 + i / 4, lap2.odom[i]);
        ASSERT_TRUE(T && U);
        EXPECT_TRUE(T->isApprox(*U, 1e-12)) << "scan " << i;
    }
}

TEST(MapperLongTerm, ALoopThatAgreesWithTheGraphMakesNoOptimisationDue) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    const MapperConfig config = test_config();
    Mapper first(config);
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), first);
    ASSERT_TRUE(first.optimise().solved);
    Mapper next(config, first.snapshot());
    // Off by 0.4 m more from keyframe 8 on: a loop there disagrees with the graph.
    const Drive again(scene, 0.5, 0.3, registration::test::xy_yaw(-20.0, 7.0, 35.0), 86400.0, 8,
                      registration::test::xy_yaw(0.4, -0.2, 0.5));
    const std::vector<KeyframeResult> kf = replay(again, next);
    std::size_t agreeing = 0, first_loop = 16, jump_loop = 16;
    for (std::size_t i = 0; i < kf.size(); ++i) {
        for (const LoopClosure& l : kf[i].loops) {
            if (first_loop == 16) first_loop = i;
            if (i >= 8 && jump_loop == 16) jump_loop = i;
            if (l.agrees) {
                ++agreeing;
                EXPECT_LE(l.disagreement, config.long_term.agree_translation);
            }
        }
    }
    ASSERT_LT(first_loop, 8u) << "no loop to the first session";
    ASSERT_LT(jump_loop, 16u) << "no loop after the odometry's jump";
    // The first loop joins the session to the map: an optimisation is due.
    EXPECT_TRUE(kf[first_loop].optimisation_due());
    EXPECT_FALSE(kf[first_loop].loops[0].agrees);
    // The first loop after the jump disagrees by about 0.4 m: due again.
    EXPECT_TRUE(kf[jump_loop].optimisation_due());
    // The others agree: added without an optimisation.
    EXPECT_GE(agreeing, 2u);
    for (std::size_t i = 0; i < kf.size(); ++i) {
        if (!kf[i].loops.empty() && kf[i].loops[0].agrees) {
            EXPECT_FALSE(kf[i].optimisation_due()) << "keyframe " << i;
        }
    }
    // With the bounds at zero every loop makes an optimisation due.
    MapperConfig strict = config;
    strict.long_term.agree_translation = 0.0;
    strict.long_term.agree_rotation = 0.0;
    Mapper other(strict, first.snapshot());
    for (const KeyframeResult& r : replay(again, other)) {
        if (!r.loops.empty()) {
            EXPECT_TRUE(r.optimisation_due());
        }
    }
}

// A second session tied to the loaded map by a localisation's poses alone (no loop closure): the
// first fix places the session, its local maps fold into the map's, and a fix that contradicts
// the graph is refused.
TEST(MapperLongTerm, LocalisationFixesPlaceASessionOnTheLoadedMapWithoutLoops) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    MapperConfig config = test_config();
    Mapper first(config);
    replay(Drive(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0), first);
    ASSERT_TRUE(first.optimise().solved);
    config.loop_closure = false;
    Mapper next(config, first.snapshot());
    const Eigen::Isometry3d T_odom_world = registration::test::xy_yaw(-20.0, 7.0, 35.0);
    const Drive again(scene, 0.5, 0.3, T_odom_world, 86400.0);
    std::size_t placed = 0, fixes = 0, merged = 0;
    for (std::size_t i = 0; i < 16; ++i) {
        const common::KeyframeData k = again.keyframe(i);
        const KeyframeResult r = next.add_keyframe(k);
        ASSERT_TRUE(r.added) << r.message;
        EXPECT_TRUE(r.loops.empty());
        const MapFixResult f = next.add_map_fix(next.session(), k.local_map_id, k.T_anchor_lidar,
                                                again.truth[i], r.index);
        fixes += f.added;
        placed += f.placed_part;
        if (f.optimisation_due) {
            ASSERT_TRUE(next.optimise().solved);
        }
        if (i % 4 == 3) merged += next.add_local_map(again.maps[i / 4]).merged;
    }
    EXPECT_EQ(placed, 1u);
    EXPECT_GE(fixes, 4u);  // at least one a local map (those folded take none)
    EXPECT_EQ(next.map_fixes(), fixes);
    EXPECT_GE(merged, 3u) << "the session's maps fold into the loaded map's";
    for (std::size_t i = 0; i < 16; ++i) {
        const std::optional<Eigen::Isometry3d> T = next.T_world_lidar(i / 4, again.odom[i]);
        ASSERT_TRUE(T);
        EXPECT_LT((T->translation() - again.truth[i].translation()).norm(), 0.05) << i;
    }
    // A fix 5 m off the graph's estimate, on a map not yet folded, is refused.
    Mapper other(config, first.snapshot());
    const Drive far(scene, 0.5, 0.3, T_odom_world, 86400.0);
    for (std::size_t i = 0; i < 6; ++i) {
        const common::KeyframeData k = far.keyframe(i);
        const KeyframeResult r = other.add_keyframe(k);
        Eigen::Isometry3d fix = far.truth[i];
        if (i == 5) fix.translation().x() += 5.0;
        const MapFixResult f =
            other.add_map_fix(other.session(), k.local_map_id, k.T_anchor_lidar, fix, r.index);
        if (f.optimisation_due) {
            ASSERT_TRUE(other.optimise().solved);
        }
        if (i == 0) {
            EXPECT_TRUE(f.added && f.placed_part) << f.message;
        }
        if (i == 5) {
            EXPECT_FALSE(f.added);
            EXPECT_NE(f.message.find("refused"), std::string::npos) << f.message;
        }
    }
}

// World centres of a mapper's voxels inside a box.
std::vector<Eigen::Vector3f> voxels_in(const Mapper& m, const Eigen::AlignedBox3f& box) {
    std::vector<Eigen::Vector3f> out;
    for (const map::StoredLocalMap& lm : m.snapshot().local_maps) {
        const Eigen::Isometry3f T =
            (m.graph().find(lm.node)->T_world_anchor * lm.data->T_anchor_grid).cast<float>();
        for (const common::VoxelData& v : lm.data->voxels) {
            const Eigen::Vector3f p = T * v.centre;
            if (box.contains(p)) out.push_back(p);
        }
    }
    return out;
}

// A finished local map (id 0, revision 1) of 0.6 m voxels in the world frame, none yet.
common::LocalMapData finished_local_map(const Eigen::Vector3d& bbox_min,
                                        const Eigen::Vector3d& bbox_max) {
    common::LocalMapData m;
    m.id = 0;
    m.revision = 1;
    m.finished = true;
    m.voxel_size = 0.6f;
    m.bbox_min = bbox_min;
    m.bbox_max = bbox_max;
    return m;
}

// A voxel of 60 points on a plane through c with normal n.
void add_planar_voxel(common::LocalMapData& m, const Eigen::Vector3f& c, const Eigen::Vector3f& n) {
    common::VoxelData v;
    v.index = (c / m.voxel_size).array().floor().cast<int>();
    v.centre = c;
    v.normal = n;
    v.point_count = 60;
    v.planarity = 0.97f;
    m.voxels.push_back(v);
}

// Whether the mapper's local maps hold a voxel centred at p (within 1 mm).
bool has_voxel(const Mapper& mapper, const Eigen::Vector3f& p) {
    const Eigen::AlignedBox3f all(Eigen::Vector3f::Constant(-100.0f),
                                  Eigen::Vector3f::Constant(100.0f));
    const std::vector<Eigen::Vector3f> v = voxels_in(mapper, all);
    return std::any_of(v.begin(), v.end(), [&](const auto& q) { return (q - p).norm() < 1e-3f; });
}

// What maintenance found gone leaves every local map, and local maps that arrive later, until a
// new object is found there.
TEST(MapperLongTerm, RemovedCellsLeaveTheLocalMapsNowAndLater) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    Mapper mapper(test_config());
    const Drive d(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0);
    replay(d, mapper);
    const Eigen::AlignedBox3f box(Eigen::Vector3f(8.0f, -10.0f, 0.5f),
                                  Eigen::Vector3f(30.0f, 10.0f, 5.0f));
    const Eigen::AlignedBox3f far_box(Eigen::Vector3f(-100.0f, -100.0f, -100.0f),
                                      Eigen::Vector3f(100.0f, 100.0f, 100.0f));
    const std::vector<Eigen::Vector3f> gone = voxels_in(mapper, box);
    ASSERT_GT(gone.size(), 20u);
    const std::size_t all = voxels_in(mapper, far_box).size();
    const std::uint64_t revision = mapper.revision();
    const Mapper::Memory memory = mapper.memory();
    EXPECT_EQ(memory.removed_cells, RemovedCells().memory_bytes());
    EXPECT_GT(memory.local_maps, all * sizeof(common::VoxelData));
    EXPECT_GT(memory.keyframes, 0u);
    const std::size_t cleared = mapper.remove_cells(gone, 0.25f);
    // The memory line's parts: the cells recorded are counted.
    EXPECT_GT(mapper.memory().removed_cells, memory.removed_cells);
    EXPECT_EQ(mapper.memory().total(), mapper.memory_bytes());
    EXPECT_GE(cleared, gone.size());
    EXPECT_EQ(mapper.removed_voxels(), cleared);
    EXPECT_GT(mapper.revision(), revision);  // the map changed: saved again
    EXPECT_TRUE(voxels_in(mapper, box).empty());
    // Only the cells' neighbourhood went (half a cell around each centre).
    EXPECT_LT(all - voxels_in(mapper, far_box).size(), gone.size() * 2);
    // A newer snapshot of a map holds the voxels again: cleared as it arrives.
    common::LocalMapData again = d.maps[2];
    again.revision += 1;
    ASSERT_TRUE(mapper.add_local_map(again).added);
    EXPECT_TRUE(voxels_in(mapper, box).empty());
    // A new object there: later snapshots keep their voxels.
    mapper.keep_cells(gone, 0.25f);
    again.revision += 1;
    ASSERT_TRUE(mapper.add_local_map(again).added);
    EXPECT_FALSE(voxels_in(mapper, box).empty());
}

// A parked car's side seen only from afar (issue 26, repeat_fortnight): the local map holds its
// lowest part as a voxel of its own (an upright plane 0.1-0.7 m above the ground, centre 0.3 m),
// while maintenance, which makes no voxel for a far return beside an earlier day's, removed the
// car's cells from 0.75 m up only. A cell of the vanished car on that voxel's plane within one
// voxel edge takes it; the ground below, a wall 0.4 m behind the side and the side's plane 1.5 m on
// stay; the same cells as moving ones (no vanished segment) or a vanished segment of fewer than
// map_edits.surface_min_cells cells leave it, as before (only cells within half its edge took a
// voxel). A snapshot of the map that arrives later is cleared the same way.
TEST(MapperLongTerm, AVanishedObjectsCellsTakeTheVoxelsOnItsSurfaceWithinAVoxelEdge) {
    common::LocalMapData m =
        finished_local_map(Eigen::Vector3d(8.0, -2.0, -2.0), Eigen::Vector3d(12.0, 4.0, 3.0));
    const auto voxel = [&](const Eigen::Vector3f& c, const Eigen::Vector3f& n) {
        add_planar_voxel(m, c, n);
    };
    const Eigen::Vector3f side_low(10.05f, 0.3f, 0.3f), ground(9.9f, 0.3f, -0.28f),
        wall(10.45f, 0.3f, 0.3f), side_far(10.05f, 1.8f, 0.3f);
    voxel(side_low, Eigen::Vector3f::UnitX());
    voxel(ground, Eigen::Vector3f::UnitZ());
    voxel(wall, Eigen::Vector3f::UnitX());
    voxel(side_far, Eigen::Vector3f::UnitX());
    // The car's side above 0.75 m, y 0-1 (its cells), as maintenance removed it.
    std::vector<Eigen::Vector3f> car;
    for (float y = 0.05f; y < 1.0f; y += 0.25f)
        for (float z = 0.8f; z < 1.5f; z += 0.25f) car.emplace_back(10.05f, y, z);
    ASSERT_GE(car.size(), 10u);
    Mapper vanished(test_config()), moving(test_config()), small(test_config());
    for (Mapper* mapper : {&vanished, &moving, &small}) ASSERT_TRUE(mapper->add_local_map(m).added);
    EXPECT_EQ(vanished.remove_cells(car, 0.25f, {car}), 1u);
    EXPECT_FALSE(has_voxel(vanished, side_low));
    for (const Eigen::Vector3f& p : {ground, wall, side_far})
        EXPECT_TRUE(has_voxel(vanished, p)) << p.transpose();
    EXPECT_EQ(moving.remove_cells(car, 0.25f), 0u);
    EXPECT_TRUE(has_voxel(moving, side_low));
    const std::vector<Eigen::Vector3f> few(car.begin(), car.begin() + 4);
    EXPECT_EQ(small.remove_cells(car, 0.25f, {few}), 0u);
    EXPECT_TRUE(has_voxel(small, side_low));
    common::LocalMapData again = m;  // a newer snapshot holds it again
    again.revision = 2;
    ASSERT_TRUE(vanished.add_local_map(again).added);
    EXPECT_FALSE(has_voxel(vanished, side_low));
    EXPECT_TRUE(has_voxel(vanished, wall));
    // Off (surface_band 0): as before.
    MapperConfig off = test_config();
    off.map_edits.surface_band = 0.0;
    Mapper without(off);
    ASSERT_TRUE(without.add_local_map(m).added);
    EXPECT_EQ(without.remove_cells(car, 0.25f, {car}), 0u);
}

// Ground stays (MapEditConfig::ground_height, long_day: two thirds of the static voxels lost were
// ground): a pedestrian who left, whose lowest removed cell holds the ground's points under its
// feet, takes its own voxels but not the ground voxel beside its feet; a car's roof (flat, 1.5 m
// above the ground around) still goes. Off (ground_height 0), the ground voxel goes as before.
TEST(MapperLongTerm, RemovedCellsLeaveTheGroundUnderAnObjectsFeet) {
    common::LocalMapData m =
        finished_local_map(Eigen::Vector3d(0.0, -5.0, -1.0), Eigen::Vector3d(12.0, 5.0, 3.0));
    const auto voxel = [&](const Eigen::Vector3f& c, const Eigen::Vector3f& n) {
        add_planar_voxel(m, c, n);
    };
    // Ground at z 0 over x 0-12, y -3..3 (one voxel a 0.6 m cell).
    for (float x = 0.3f; x < 12.0f; x += 0.6f)
        for (float y = -2.7f; y < 3.0f; y += 0.6f)
            voxel(Eigen::Vector3f(x, y, 0.0f), Eigen::Vector3f::UnitZ());
    const Eigen::Vector3f feet_ground(6.3f, 0.3f, 0.0f), body(6.2f, 0.25f, 0.9f),
        roof(9.9f, 0.3f, 1.5f);
    voxel(body, Eigen::Vector3f::UnitX());
    voxel(roof, Eigen::Vector3f::UnitZ());
    // The pedestrian's cells (0.25 m) from the ground's cell up, the roof's cell.
    std::vector<Eigen::Vector3f> cells;
    for (float z = 0.125f; z < 1.8f; z += 0.25f) cells.emplace_back(6.375f, 0.375f, z);
    cells.emplace_back(9.875f, 0.375f, 1.375f);
    const Eigen::AlignedBox3f all(Eigen::Vector3f(-100.0f, -100.0f, -100.0f),
                                  Eigen::Vector3f(100.0f, 100.0f, 100.0f));
    Mapper guarded(test_config());
    ASSERT_TRUE(guarded.add_local_map(m).added);
    EXPECT_EQ(guarded.remove_cells(cells, 0.25f), 2u);
    EXPECT_FALSE(has_voxel(guarded, body));
    EXPECT_FALSE(has_voxel(guarded, roof));
    EXPECT_TRUE(has_voxel(guarded, feet_ground));
    EXPECT_EQ(voxels_in(guarded, all).size(), m.voxels.size() - 2);
    MapperConfig off = test_config();
    off.map_edits.ground_height = 0.0;
    Mapper unguarded(off);
    ASSERT_TRUE(unguarded.add_local_map(m).added);
    EXPECT_EQ(unguarded.remove_cells(cells, 0.25f), 3u);
    EXPECT_FALSE(has_voxel(unguarded, feet_ground));
}

// The same edits in steps (issue 28: spread over the mapping's thread, one local map a step)
// end as the edits at once: the same voxels left, the same count; until then the maps not yet
// cleared still hold theirs, and a map that arrives meanwhile is cleared as it arrives.
TEST(MapperLongTerm, RemovedCellsInStepsEndAsAtOnce) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(71));
    const Drive d(scene, 0.0, 0.0, Eigen::Isometry3d::Identity(), 0.0);
    Mapper at_once(test_config()), stepped(test_config());
    replay(d, at_once);
    replay(d, stepped);
    const Eigen::AlignedBox3f box(Eigen::Vector3f(8.0f, -10.0f, 0.5f),
                                  Eigen::Vector3f(30.0f, 10.0f, 5.0f));
    const Eigen::AlignedBox3f far_box(Eigen::Vector3f(-100.0f, -100.0f, -100.0f),
                                      Eigen::Vector3f(100.0f, 100.0f, 100.0f));
    const std::vector<Eigen::Vector3f> gone = voxels_in(at_once, box);
    ASSERT_GT(gone.size(), 20u);
    const std::size_t cleared = at_once.remove_cells(gone, 0.25f);

    const std::size_t waiting = stepped.remove_cells_in_steps(gone, 0.25f);
    ASSERT_GE(waiting, 2u) << "the box spans several local maps";
    EXPECT_EQ(stepped.removal_waiting(), waiting);
    EXPECT_EQ(stepped.removed_voxels(), 0u);  // nothing cleared before a step
    EXPECT_EQ(voxels_in(stepped, box).size(), gone.size());
    std::size_t steps = 0, sum = 0, removed = 0, arrived = 0;
    bool more = true;
    while (more) {
        more = stepped.clear_removed_step(&removed);
        sum += removed;
        ++steps;
        if (steps == 1) {
            // One map cleared, the others not yet.
            EXPECT_GT(voxels_in(stepped, box).size(), 0u);
            EXPECT_LT(voxels_in(stepped, box).size(), gone.size());
            // A map arriving meanwhile is cleared as it arrives (the cells are recorded).
            common::LocalMapData again = d.maps[2];
            again.revision += 1;
            const std::size_t before = stepped.removed_voxels();
            ASSERT_TRUE(stepped.add_local_map(again).added);
            arrived = stepped.removed_voxels() - before;
        }
    }
    EXPECT_EQ(steps, waiting);
    EXPECT_FALSE(stepped.clear_removed_step());
    EXPECT_EQ(stepped.removal_waiting(), 0u);
    EXPECT_EQ(sum + arrived, stepped.removed_voxels());
    EXPECT_TRUE(voxels_in(stepped, box).empty());
    EXPECT_EQ(voxels_in(stepped, far_box).size(), voxels_in(at_once, far_box).size());
    EXPECT_EQ(at_once.removed_voxels(), cleared);
}

// A map folded into a node that is itself folded later names the node it went into, with its
// anchor composed: nothing may name a node that left the graph.
TEST(LongTermFolding, MapsFoldedIntoAFoldedNodeFollowIt) {
    LongTermFolding folding;
    LongTermFolding::Folded f;
    f.node = 5;
    f.T_node_anchor = registration::test::xy_yaw(2.0, 0.0, 0.0);
    folding.record(1, 12, f);
    f.node = 6;
    folding.record(1, 13, f);
    const Eigen::Isometry3d T_into_n = registration::test::xy_yaw(0.0, 3.0, 90.0);
    const auto moved = folding.retarget(5, 1, T_into_n);
    ASSERT_EQ(moved.size(), 1u);
    EXPECT_EQ(moved[0], std::make_pair(std::uint32_t(1), std::uint64_t(12)));
    ASSERT_NE(folding.find(1, 12), nullptr);
    EXPECT_EQ(folding.find(1, 12)->node, 1u);
    EXPECT_TRUE(folding.find(1, 12)->T_node_anchor.isApprox(
        T_into_n * registration::test::xy_yaw(2.0, 0.0, 0.0)));
    EXPECT_EQ(folding.find(1, 13)->node, 6u);
}

TEST(MapFixPairer, PairsAKeyframeWithATrackedPoseInAnyOrderAfterARunOfTracking) {
    MapFixPairer pairer(3);
    FixKeyframe kf;
    kf.local_map_id = 7;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(1, 2, 3);
    // Scans 0.1 .. 0.3 tracked; the keyframe at 0.2 comes before its state: not yet 3 in a row.
    EXPECT_FALSE(pairer.state(0.1, true));
    EXPECT_FALSE(pairer.pose(0.1, T));
    EXPECT_FALSE(pairer.keyframe(0.2, kf));
    EXPECT_FALSE(pairer.pose(0.2, T));
    EXPECT_FALSE(pairer.state(0.2, true));  // run of 2: no fix
    // The third tracked scan: keyframe first, then pose, then state.
    EXPECT_FALSE(pairer.keyframe(0.3, kf));
    EXPECT_FALSE(pairer.pose(0.3, T));
    const std::optional<PairedFix> f = pairer.state(0.3, true);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->keyframe.local_map_id, 7u);
    EXPECT_TRUE(f->T_world_lidar.isApprox(T));
    // Not tracking (lost, off the map): no fix, and the run starts again.
    EXPECT_FALSE(pairer.state(0.4, false));
    EXPECT_FALSE(pairer.keyframe(0.4, kf));
    EXPECT_FALSE(pairer.pose(0.4, T));
    EXPECT_FALSE(pairer.state(0.5, true));
    EXPECT_FALSE(pairer.pose(0.5, T));
    EXPECT_FALSE(pairer.keyframe(0.5, kf));
}

// The blocks' pre-check answers as the cells alone: every probe near and far from the cells
// (both signs, across block edges), with and without a radius, after adds and erases, against a
// brute force over the cells recorded.
TEST(RemovedCells, AnswersAsABruteForceOverTheCells) {
    const float size = 0.25f;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-6.0f, 6.0f);
    std::vector<Eigen::Vector3f> centres;
    for (int i = 0; i < 120; ++i) centres.emplace_back(u(rng), u(rng), u(rng) / 4);
    RemovedCells cells;
    cells.add(centres, size);
    std::vector<Eigen::Vector3f> erased(centres.begin(), centres.begin() + 40);
    cells.erase(erased);
    std::set<std::array<int, 3>> kept;
    for (std::size_t i = 40; i < centres.size(); ++i) {
        const Eigen::Vector3i c = (centres[i] / size).array().floor().cast<int>();
        kept.insert({c.x(), c.y(), c.z()});
    }
    for (const Eigen::Vector3f& e : erased) {  // a cell erased after another centre put it back
        const Eigen::Vector3i c = (e / size).array().floor().cast<int>();
        kept.erase({c.x(), c.y(), c.z()});
    }
    ASSERT_EQ(cells.size(), kept.size());
    const auto brute = [&](const Eigen::Vector3f& p, float radius) {
        const Eigen::Vector3f q = p / size;
        for (const auto& k : kept) {
            const Eigen::Vector3f cell = Eigen::Vector3i(k[0], k[1], k[2]).cast<float>();
            const Eigen::Vector3f centre = (cell.array() + 0.5f) * size;
            // The 2x2x2 cells nearest to p: each axis within one cell of p's cell centre.
            bool near = true;
            for (int a = 0; a < 3; ++a) near = near && std::abs(q[a] - (float(k[a]) + 0.5f)) < 1.0f;
            if (near) return true;
            if (radius > 0.0f && (centre - p).squaredNorm() <= radius * radius) return true;
        }
        return false;
    };
    std::size_t hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const Eigen::Vector3f p(u(rng), u(rng), u(rng) / 4);
        const bool a = cells.covers(p), b = cells.covers(p, 0.3f);
        EXPECT_EQ(a, brute(p, 0.0f)) << p.transpose();
        EXPECT_EQ(b, brute(p, 0.3f)) << p.transpose();
        hits += b;
    }
    EXPECT_GT(hits, 50u);
    EXPECT_LT(hits, 3950u);
}

TEST(RemovedCells, CoversTheCellAndHalfACellAround) {
    RemovedCells cells;
    EXPECT_FALSE(cells.covers(Eigen::Vector3f(0.1f, 0.1f, 0.1f)));
    EXPECT_EQ(
        cells.add({Eigen::Vector3f(0.1f, 0.1f, 0.1f), Eigen::Vector3f(std::nanf(""), 0.0f, 0.0f)},
                  0.25f),
        1u);
    EXPECT_TRUE(cells.covers(Eigen::Vector3f(0.2f, 0.05f, 0.0f)));
    EXPECT_TRUE(cells.covers(Eigen::Vector3f(0.3f, 0.1f, 0.1f)));    // 0.05 beyond the cell
    EXPECT_FALSE(cells.covers(Eigen::Vector3f(0.45f, 0.1f, 0.1f)));  // 0.2 beyond
    EXPECT_FALSE(cells.covers(Eigen::Vector3f(-0.2f, 0.1f, 0.1f)));
    cells.erase({Eigen::Vector3f(0.2f, 0.2f, 0.2f)});
    EXPECT_TRUE(cells.empty());
    RemovedCells small(1);
    small.add({Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(5, 5, 5)}, 0.25f);
    EXPECT_TRUE(small.full());
    EXPECT_EQ(small.size(), 1u);
}

}  // namespace
}  // namespace ltm::mapping
