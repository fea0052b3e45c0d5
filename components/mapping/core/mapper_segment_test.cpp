// Odometry segments in the Mapper: the odometry lost track and restarted at a wrong estimate
// (common::LocalMapData::segment), a loop joins the new segment to the map.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "map/core/map_store.hpp"
#include "mapping/core/mapper.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

constexpr double kDeg = M_PI / 180.0;

double angle_deg(const Eigen::Isometry3d& T) {
    return Eigen::AngleAxisd(T.linear()).angle() / kDeg;
}

// A synthetic scene driven east along y = 0 (keyframes 0-7 every 3 m, local maps 0 and 1), then,
// after a turn the odometry lost, west along y = 2 (keyframes 8-15, local maps 2 and 3), past the
// places of the first pass in the other direction. The odometry restarted at local map 2's anchor
// `break_error` off (5 m, 40 deg) and tracked well from there: the second pass is off by that
// error, rigidly.
struct LostAndBack {
    std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(61));
    Eigen::Isometry3d break_error =
        registration::test::xy_yaw(3.0, 4.0, 40.0);                  // at local map 2's anchor
    Eigen::Isometry3d T_odom_world = Eigen::Isometry3d::Identity();  // of the second pass
    common::PoseList truth, odom;
    std::vector<std::uint64_t> map_of;
    std::vector<std::vector<Eigen::Vector3f>> points;
    std::vector<common::LocalMapData> maps;

    explicit LostAndBack(std::uint32_t second_segment) {
        for (int i = 0; i < 16; ++i) {
            truth.push_back(i < 8 ? registration::test::xy_yaw(3.0 * i, 0.0, 0.0)
                                  : registration::test::xy_yaw(24.0 - 3.0 * (i - 8), 2.0, 180.0));
            map_of.push_back(std::uint64_t(i / 4));
            points.push_back(registration::test::view(scene, truth.back(), 50.0));
        }
        T_odom_world = truth[8] * break_error * truth[8].inverse();
        for (int i = 0; i < 16; ++i) odom.push_back(i < 8 ? truth[i] : T_odom_world * truth[i]);
        for (std::uint64_t m = 0; m < 4; ++m) {
            std::vector<std::vector<Eigen::Vector3f>> scans;
            common::PoseList poses;
            for (std::size_t i = 4 * m; i < 4 * m + 4; ++i) {
                scans.push_back(points[i]);
                poses.push_back(odom[i]);
            }
            maps.push_back(registration::test::build_local_map(m, poses.front(), scans, poses));
            maps.back().segment = m < 2 ? 0 : second_segment;
        }
    }

    common::KeyframeData keyframe(std::size_t i) const {
        common::KeyframeData k;
        k.id = i;
        k.scan_index = i;
        k.local_map_id = map_of[i];
        k.stamp = double(i);
        k.T_odom_lidar = odom[i];
        k.T_anchor_lidar = maps[map_of[i]].T_odom_anchor.inverse() * odom[i];
        k.points = points[i];
        return k;
    }
    // The true world pose of local map m's anchor (the world is the first pass's odometry frame).
    Eigen::Isometry3d true_anchor(std::uint64_t m) const {
        return m < 2 ? maps[m].T_odom_anchor : T_odom_world.inverse() * maps[m].T_odom_anchor;
    }
};

MapperConfig segment_config() {
    MapperConfig c;
    c.loop_detection.exclude_recent_keyframes = 6;
    c.loop_detection.exclude_recent_seconds = 0.0;
    c.loop_detection.max_distance = 0.6;  // the passes are 2 m apart, facing each other
    c.loop_detection.max_results = 1;     // the best candidate only: a fast test
    c.loop_cooldown_keyframes = 1;
    return c;
}

// The local maps an edge of the weak kind (across a segment break) leads to.
std::vector<std::uint64_t> break_targets(const Mapper& mapper) {
    std::vector<std::uint64_t> to;
    for (const map::PoseGraphEdge& e : mapper.graph().edges()) {
        if (is_segment_break(e)) to.push_back(mapper.graph().find(e.to)->local_map_id);
    }
    return to;
}

// Every other keyframe (few points: no loops), before any local map arrives; each saying its
// segment, as the odometry's do, or not.
void add_keyframes_without_maps(const LostAndBack& s, Mapper& mapper, bool say_segment) {
    for (std::size_t i = 0; i < 16; i += 2) {
        common::KeyframeData k = s.keyframe(i);
        k.points.resize(100);
        if (say_segment) k.segment = s.maps[s.map_of[i]].segment;
        ASSERT_TRUE(mapper.add_keyframe(k).added);
    }
}

// Keyframes 0 to count - 1; each local map arrives before its keyframes (a snapshot with its
// segment); the graph is optimised when a loop is accepted, as the pipeline does.
std::vector<KeyframeResult> replay(const LostAndBack& s, Mapper& mapper, std::size_t count = 16) {
    std::vector<KeyframeResult> out;
    for (std::size_t i = 0; i < count; ++i) {
        if (i % 4 == 0) {
            EXPECT_TRUE(mapper.add_local_map(s.maps[s.map_of[i]]).added);
        }
        out.push_back(mapper.add_keyframe(s.keyframe(i)));
        EXPECT_TRUE(out.back().added) << out.back().message;
        if (out.back().optimisation_due()) {
            EXPECT_TRUE(mapper.optimise().solved);
        }
    }
    return out;
}

TEST(MapperSegments, ALoopAcrossTheBreakIsAcceptedAndPutsTheNewSegmentInPlace) {
    const LostAndBack s(1);
    Mapper mapper(segment_config());
    // Before the loop: segment 1 not joined, its maps at the odometry's best estimate.
    for (std::size_t i = 0; i < 4; ++i) ASSERT_TRUE(mapper.add_local_map(s.maps[i]).added);
    std::vector<SegmentStatus> st = mapper.segments();
    ASSERT_EQ(st.size(), 2u);
    EXPECT_TRUE(st[0].joined);
    EXPECT_FALSE(st[1].joined);
    EXPECT_EQ(st[1].first_local_map, 2u);
    EXPECT_NE(st[1].message.find("not joined to the map yet"), std::string::npos) << st[1].message;
    EXPECT_TRUE(mapper.T_world_odom(2)->isApprox(Eigen::Isometry3d::Identity(), 1e-9));
    // Its edge from map 1 is the weak one, the others odometry.
    int breaks = 0;
    for (const map::PoseGraphEdge& e : mapper.graph().edges()) breaks += is_segment_break(e);
    EXPECT_EQ(breaks, 1);

    const std::vector<KeyframeResult> results = replay(s, mapper);
    // The first loop of segment 1 (segment 0 closes one of its own at keyframe 7).
    const LoopClosure* joining = nullptr;
    for (const LoopClosure& l : mapper.loops()) {
        if (!joining && l.query_segment == 1) joining = &l;
    }
    ASSERT_TRUE(joining) << "no loop across the break";
    const LoopClosure& first = *joining;
    EXPECT_TRUE(first.across_break);
    EXPECT_FALSE(first.from_graph_guess);
    EXPECT_EQ(first.query_segment, 1u);
    EXPECT_EQ(first.match_segment, 0u);
    EXPECT_GT(first.disagreement, 4.0);  // with the graph's estimate across the break
    for (const LoopClosure& l : mapper.loops()) {
        const Eigen::Isometry3d truth = s.truth[l.match_scan].inverse() * s.truth[l.query_scan];
        const Eigen::Isometry3d err = truth.inverse() * l.T_match_query;
        EXPECT_LT(err.translation().norm(), 0.05) << l.query_scan << " -> " << l.match_scan;
        EXPECT_LT(angle_deg(err), 0.3) << l.query_scan << " -> " << l.match_scan;
    }
    // Optimised: every anchor of both segments on the truth.
    ASSERT_TRUE(mapper.optimise().solved);
    for (std::uint64_t m = 0; m < 4; ++m) {
        const Eigen::Isometry3d err =
            s.true_anchor(m).inverse() * mapper.graph().find(*mapper.node_of(m))->T_world_anchor;
        EXPECT_LT(err.translation().norm(), 0.03) << "local map " << m;
        EXPECT_LT(angle_deg(err), 0.1) << "local map " << m;
    }
    // The correction of segment 1's odometry frame undoes the break.
    const Eigen::Isometry3d c = *mapper.T_world_odom(3) * s.T_odom_world;
    EXPECT_LT(c.translation().norm(), 0.03);
    EXPECT_LT(angle_deg(c), 0.1);
    st = mapper.segments();
    ASSERT_EQ(st.size(), 2u);
    EXPECT_TRUE(st[1].joined);
    EXPECT_EQ(st[1].joined_at_keyframe, first.query_keyframe);
    EXPECT_EQ(st[1].message, "segment 1 joined to the map by a loop at keyframe " +
                                 std::to_string(first.query_keyframe));
}

TEST(MapperSegments, WithoutTheBreakTheConsistencyBoundStillRefusesThatLoop) {
    const LostAndBack s(0);  // the same data, one segment: an odometry that jumped
    Mapper mapper(segment_config());
    // Up to keyframe 12: keyframe 11 closes the loop across the break when there is one.
    const std::vector<KeyframeResult> results = replay(s, mapper, 13);
    for (const LoopClosure& l : mapper.loops())
        EXPECT_LT(l.query_scan, 8u) << "a loop accepted across the jump";
    std::size_t refused = 0;
    for (const KeyframeResult& r : results) {
        for (const LoopRejection& j : r.rejected)
            refused += j.reason.find("disagrees with the graph") != std::string::npos;
    }
    EXPECT_GE(refused, 1u);
    ASSERT_EQ(mapper.segments().size(), 1u);
}

// The optimisation run elsewhere (graph_snapshot, PoseGraph::optimise, apply) joins the segment
// alike.
TEST(MapperSegments, AnOptimisationAppliedFromElsewhereJoinsTheSegmentAlike) {
    const LostAndBack s(1);
    Mapper here(segment_config()), elsewhere(segment_config());
    for (Mapper* m : {&here, &elsewhere}) {
        for (std::size_t i = 0; i < 16; ++i) {
            if (i % 4 == 0) {
                ASSERT_TRUE(m->add_local_map(s.maps[s.map_of[i]]).added);
            }
            const KeyframeResult r = m->add_keyframe(s.keyframe(i));
            ASSERT_TRUE(r.added) << r.message;
            if (!r.optimisation_due()) continue;
            if (m == &here) {
                ASSERT_TRUE(m->optimise().solved);
            } else {
                PoseGraph g = m->graph_snapshot();
                const OptimisationSummary summary = g.optimise();
                ASSERT_TRUE(m->apply(g, summary));
            }
        }
    }
    ASSERT_EQ(here.segments().size(), 2u);
    ASSERT_EQ(elsewhere.segments().size(), 2u);
    EXPECT_TRUE(here.segments()[1].joined);
    EXPECT_EQ(elsewhere.segments()[1].message, here.segments()[1].message);
    for (std::uint64_t m = 0; m < 4; ++m) {
        const Eigen::Isometry3d d = here.graph().find(*here.node_of(m))->T_world_anchor.inverse() *
                                    elsewhere.graph().find(*elsewhere.node_of(m))->T_world_anchor;
        EXPECT_LT(d.translation().norm(), 1e-6) << "local map " << m;
    }
}

// The odometry hands a keyframe over before its local map: the node takes the segment of the map
// before it, and the edge becomes the weak one when the map says it starts a segment.
TEST(MapperSegments, ASegmentLearntFromALateLocalMapRelinksTheEdges) {
    const LostAndBack s(1);
    Mapper mapper(segment_config());
    add_keyframes_without_maps(s, mapper, false);
    auto breaks = [&] { return break_targets(mapper); };
    EXPECT_TRUE(breaks().empty());
    EXPECT_EQ(mapper.segment_of(*mapper.node_of(3)), 0u);
    ASSERT_TRUE(mapper.add_local_map(s.maps[2]).added);  // segment 1 starts at map 2
    EXPECT_EQ(breaks(), std::vector<std::uint64_t>{2});
    EXPECT_EQ(mapper.segment_of(*mapper.node_of(3)), 1u);  // taken from map 2
    EXPECT_EQ(mapper.graph().edges().size(), 3u);
    ASSERT_TRUE(mapper.add_local_map(s.maps[3]).added);
    EXPECT_EQ(breaks(), std::vector<std::uint64_t>{2});
    // A break the odometry reports at map 3 instead (a later snapshot with another number).
    common::LocalMapData later = s.maps[2];
    later.segment = 0;
    later.revision = 2;
    ASSERT_TRUE(mapper.add_local_map(later).added);
    EXPECT_EQ(breaks(), std::vector<std::uint64_t>{3});
    EXPECT_EQ(mapper.graph().edges().size(), 3u);
    // The graph is well posed all along: one part, the break's measurement kept.
    const OptimisationSummary r = mapper.optimise();
    ASSERT_TRUE(r.solved) << r.message;
    EXPECT_EQ(r.components, 1u);
}

// A keyframe that says its segment (as the odometry's do) places its node at once: the weak edge
// is there before any local map of the new segment arrives (over a link, a map comes when
// finished).
TEST(MapperSegments, AKeyframeThatSaysItsSegmentMakesTheBreakAtOnce) {
    const LostAndBack s(1);
    Mapper mapper(segment_config());
    add_keyframes_without_maps(s, mapper, true);
    EXPECT_EQ(break_targets(mapper), std::vector<std::uint64_t>{2});
    const std::vector<SegmentStatus> st = mapper.segments();
    ASSERT_EQ(st.size(), 2u);
    EXPECT_EQ(st[1].first_local_map, 2u);
    EXPECT_EQ(mapper.segment_of(*mapper.node_of(3)), 1u);
}

// A segment that no loop has joined follows the corrections of the map before it: its anchors
// keep the odometry's best estimate across the break relative to that map. Here a saved graph
// (the file keeps no segment numbers: the break is known from its edge) is continued and
// optimised without holding it.
TEST(MapperSegments, AnUnjoinedSegmentFollowsTheCorrectionsOfTheMapsBeforeIt) {
    const MapperConfig c;
    map::MapData loaded;
    loaded.descriptor_config = c.scan_context;
    for (std::uint64_t i = 0; i < 5; ++i) {
        map::PoseGraphNode n;
        n.id = i;
        n.local_map_id = i;
        n.T_odom_anchor = n.T_world_anchor = registration::test::xy_yaw(10.0 * double(i), 0.0, 0.0);
        loaded.nodes.push_back(n);
    }
    for (std::uint64_t i = 0; i + 1 < 5; ++i) {
        map::PoseGraphEdge e;
        e.from = i;
        e.to = i + 1;
        e.T_from_to = registration::test::xy_yaw(10.0, 0.0, 0.0);
        // Segment 1 starts at node 3.
        e.information =
            i == 2 ? segment_break_information() : odometry_information(c.odometry_edge, 10.0);
        loaded.edges.push_back(e);
    }
    // A loop in segment 0 that bends node 2 by 1 m and 3 deg.
    map::PoseGraphEdge loop;
    loop.from = 0;
    loop.to = 2;
    loop.kind = map::EdgeKind::kLoop;
    loop.T_from_to = registration::test::xy_yaw(20.0, 1.0, 3.0);
    loop.information = loop_information(c.loop_edge);
    loaded.edges.push_back(loop);
    const std::string dir = std::string(LTM_BINARY_DIR) + "/mapping_test_maps/segment_break";
    std::filesystem::remove_all(dir);
    map::save_map(dir, loaded);
    const map::LoadedMap file = map::load_map(dir);
    ASSERT_TRUE(file.refused.empty()) << file.refused[0];
    Mapper mapper(c, file.map, false);
    EXPECT_EQ(mapper.segment_of(2), 0u);
    EXPECT_EQ(mapper.segment_of(3), 1u);
    EXPECT_EQ(mapper.segment_of(4), 1u);
    const OptimisationSummary r = mapper.optimise();
    ASSERT_TRUE(r.solved) << r.message;
    const Eigen::Isometry3d T2 = mapper.graph().find(2)->T_world_anchor;
    EXPECT_GT((T2.translation() - Eigen::Vector3d(20, 0, 0)).norm(), 0.1);  // node 2 moved
    for (std::uint64_t i = 3; i < 5; ++i) {
        const Eigen::Isometry3d expected =
            T2 * registration::test::xy_yaw(10.0 * double(i - 2), 0.0, 0.0);
        const Eigen::Isometry3d err = expected.inverse() * mapper.graph().find(i)->T_world_anchor;
        EXPECT_LT(err.translation().norm(), 1e-6) << "node " << i;
        EXPECT_LT(angle_deg(err), 1e-6) << "node " << i;
    }
}

}  // namespace
}  // namespace ltm::mapping
