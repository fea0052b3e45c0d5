// Several robots at once in one Mapper (open_session): two robots' sessions fed interleaved join
// into one graph by loops found either way, each placed on the truth; a robot that never meets the
// other stays where its own odometry puts it and says so; the map records each session's robot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "map/core/map_store.hpp"
#include "mapping/core/mapper.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

constexpr double kDeg = M_PI / 180.0;

double angle_deg(const Eigen::Isometry3d& T) {
    return Eigen::AngleAxisd(T.linear()).angle() / kDeg;
}

// A drive along any route over the synthetic scene: keyframe i at truth[i], local maps of 4
// keyframes each, its odometry frame its first pose.
struct Route {
    common::PoseList truth, odom;
    std::vector<std::vector<Eigen::Vector3f>> points;
    std::vector<common::LocalMapData> maps;
    Eigen::Isometry3d T_odom_world = Eigen::Isometry3d::Identity();
    double stamp0 = 0.0;

    Route(const std::vector<Eigen::Vector3f>& scene, const common::PoseList& poses, double t0)
        : truth(poses), T_odom_world(poses.front().inverse()), stamp0(t0) {
        for (const Eigen::Isometry3d& T : truth) {
            points.push_back(registration::test::view(scene, T, 50.0));
            odom.push_back(T_odom_world * T);
        }
        for (std::uint64_t m = 0; 4 * m < truth.size(); ++m) {
            const std::size_t end = std::min(truth.size(), std::size_t(4 * m + 4));
            std::vector<std::vector<Eigen::Vector3f>> scans(points.begin() + 4 * m,
                                                            points.begin() + end);
            common::PoseList p(odom.begin() + 4 * m, odom.begin() + end);
            maps.push_back(registration::test::build_local_map(m, p.front(), scans, p));
        }
    }

    common::KeyframeData keyframe(std::size_t i) const {
        common::KeyframeData k;
        k.id = i;
        k.scan_index = i;
        k.local_map_id = i / 4;
        k.stamp = stamp0 + double(i);
        k.T_odom_lidar = odom[i];
        k.T_anchor_lidar = maps[i / 4].T_odom_anchor.inverse() * odom[i];
        k.points = points[i];
        return k;
    }
};

// One robot's drive over a synthetic scene: 16 keyframes 3 m apart along y = y0 from x0 (east,
// or west when `west`), local maps 0-3 of 4 keyframes each (every robot numbers its own maps from
// 0). Its odometry starts at the identity where it starts: its odometry frame is its first pose.
struct Robot : Route {
    Robot(const std::vector<Eigen::Vector3f>& scene, double x0, double y0, bool west, double t0)
        : Route(scene, straight(x0, y0, west), t0) {}
    static common::PoseList straight(double x0, double y0, bool west) {
        common::PoseList poses;
        for (int i = 0; i < 16; ++i)
            poses.push_back(west ? registration::test::xy_yaw(x0 - 3.0 * i, y0, 180.0)
                                 : registration::test::xy_yaw(x0 + 3.0 * i, y0, 0.0));
        return poses;
    }
};

MapperConfig robots_config() {
    MapperConfig c;
    c.loop_detection.exclude_recent_keyframes = 6;
    c.loop_detection.exclude_recent_seconds = 0.0;
    c.loop_detection.max_distance = 0.6;  // the robots pass 2 m apart, facing each other
    c.loop_detection.max_results = 1;     // the best candidate only: a fast test
    c.loop_cooldown_keyframes = 1;
    return c;
}

// Both robots at once: keyframe i of robot 2, then keyframe i of robot 1 (robot 2's data arrives
// first, yet robot 1's session, the map's first, keeps its frame); each local map arrives
// before its keyframes; the graph is optimised when a loop is accepted, as the component does.
void interleave(const Robot& r1, const Robot& r2, std::uint32_t s1, std::uint32_t s2,
                Mapper& mapper) {
    for (std::size_t i = 0; i < 16; ++i) {
        for (const auto& [robot, session] : {std::make_pair(&r2, s2), std::make_pair(&r1, s1)}) {
            if (i % 4 == 0) {
                const LocalMapResult m = mapper.add_local_map(robot->maps[i / 4], session);
                EXPECT_TRUE(m.added) << m.message;
            }
            const KeyframeResult k = mapper.add_keyframe(robot->keyframe(i), session);
            EXPECT_TRUE(k.added) << k.message;
            if (k.optimisation_due()) {
                EXPECT_TRUE(mapper.optimise().solved);
            }
        }
    }
}

// Robot 1 drives east along y = 0 from x = 0; robot 2 at the same time west along y = 2 from
// x = 45, its odometry frame 45 m and 180 deg from robot 1's (which is the world here). They meet
// half-way: from then on each one drives where the other has just been.
TEST(MapperMultiRobot, TwoRobotsInterleavedJoinIntoOneGraphEachOnTheTruth) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(61));
    const Robot r1(scene, 0.0, 0.0, false, 100.0), r2(scene, 45.0, 2.0, true, 100.5);
    Mapper mapper(robots_config());
    const std::uint32_t s1 = mapper.open_session("robot1");
    const std::uint32_t s2 = mapper.open_session("robot2");
    EXPECT_EQ(s1, mapper.session());  // the default session, unused, is the first robot's
    EXPECT_NE(s2, s1);
    EXPECT_EQ(mapper.open_session("robot2"), s2);
    EXPECT_EQ(mapper.robot(s2), "robot2");
    EXPECT_EQ(mapper.open_sessions(), (std::vector<std::uint32_t>{s1, s2}));
    EXPECT_FALSE(mapper.add_keyframe(r1.keyframe(0), s2 + 7).added);

    interleave(r1, r2, s1, s2, mapper);

    // Loops between the robots, found either way, each with the true relative pose.
    std::size_t from_1 = 0, from_2 = 0;
    for (const LoopClosure& l : mapper.loops()) {
        const Robot& q = l.query_session == s1 ? r1 : r2;
        const Robot& m = l.match_session == s1 ? r1 : r2;
        from_1 += l.query_session == s1 && l.match_session == s2;
        from_2 += l.query_session == s2 && l.match_session == s1;
        const Eigen::Isometry3d truth = m.truth[l.match_scan].inverse() * q.truth[l.query_scan];
        const Eigen::Isometry3d err = truth.inverse() * l.T_match_query;
        EXPECT_LT(err.translation().norm(), 0.05) << l.query_scan << " -> " << l.match_scan;
        EXPECT_LT(angle_deg(err), 0.3) << l.query_scan << " -> " << l.match_scan;
    }
    EXPECT_GE(from_1, 1u) << "robot 1 found no place of robot 2";
    EXPECT_GE(from_2, 1u) << "robot 2 found no place of robot 1";

    // One graph: one connected part, robot 2 joined to the map by a loop.
    const OptimisationSummary o = mapper.optimise();
    ASSERT_TRUE(o.solved) << o.message;
    EXPECT_EQ(o.components, 1u);
    EXPECT_EQ(mapper.placed_parts(), 1u);
    EXPECT_TRUE(mapper.session_status(s1).joined);
    const SessionStatus st = mapper.session_status(s2);
    EXPECT_TRUE(st.joined) << st.message;
    EXPECT_NE(st.message.find("session 1 (robot2) joined to the map by a loop at keyframe"),
              std::string::npos)
        << st.message;

    // Each robot's keyframes on the truth (the world is robot 1's odometry frame, whose first map
    // holds the gauge), and robot 2's odometry frame corrected onto the world.
    for (const auto& [robot, session] : {std::make_pair(&r1, s1), std::make_pair(&r2, s2)}) {
        for (std::size_t i = 0; i < 16; ++i) {
            const std::optional<Eigen::Isometry3d> T =
                mapper.T_world_lidar(i / 4, robot->odom[i], session);
            ASSERT_TRUE(T);
            const Eigen::Isometry3d err = robot->truth[i].inverse() * *T;
            EXPECT_LT(err.translation().norm(), 0.05) << "session " << session << " keyframe " << i;
            EXPECT_LT(angle_deg(err), 0.2) << "session " << session << " keyframe " << i;
        }
    }
    const Eigen::Isometry3d c = *mapper.T_world_odom(3, s2) * r2.T_odom_world;
    EXPECT_LT(c.translation().norm(), 0.05);
    EXPECT_LT(angle_deg(c), 0.2);
    // The default-session calls are robot 1's.
    EXPECT_TRUE(mapper.T_world_odom(2)->isApprox(*mapper.T_world_odom(2, s1), 1e-12));

    // The saved map records each session with its robot; a map continued from it knows them.
    const std::vector<map::SessionRecord> records = mapper.sessions();
    ASSERT_EQ(records.size(), 2u);
    EXPECT_EQ(records[0].robot, "robot1");
    EXPECT_EQ(records[1].robot, "robot2");
    EXPECT_EQ(records[1].local_maps_added + records[1].local_maps_updated, 4u);
    const std::string dir = std::string(LTM_BINARY_DIR) + "/mapping_test_maps/two_robots";
    std::filesystem::remove_all(dir);
    map::save_map(dir, mapper.snapshot());
    const map::LoadedMap loaded = map::load_map(dir);
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused[0];
    ASSERT_EQ(loaded.map.sessions.size(), 2u);
    EXPECT_EQ(loaded.map.sessions[1].robot, "robot2");
    EXPECT_EQ(loaded.map.sessions[1].first_stamp, records[1].first_stamp);
    const Mapper continued(robots_config(), loaded.map);
    EXPECT_EQ(continued.robot(s2), "robot2");
    EXPECT_EQ(continued.session(), s2 + 1);
    EXPECT_EQ(continued.graph().nodes().size(), mapper.graph().nodes().size());
}

// The first loop between two robots' parts is held until another agrees (a repetitive site can
// fool a verification once): asked for more agreeing loops than the drive gives, the robots stay
// apart, every loop between them held and said so.
TEST(MapperMultiRobot, LoopsBetweenTwoRobotsAreHeldUntilEnoughAgree) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(61));
    const Robot r1(scene, 0.0, 0.0, false, 100.0), r2(scene, 45.0, 2.0, true, 100.5);
    MapperConfig c = robots_config();
    c.session_join.loops = 100;
    Mapper mapper(c);
    const std::uint32_t s1 = mapper.open_session("robot1");
    const std::uint32_t s2 = mapper.open_session("robot2");
    std::size_t held = 0;
    for (std::size_t i = 0; i < 16; ++i) {
        for (const auto& [robot, session] : {std::make_pair(&r2, s2), std::make_pair(&r1, s1)}) {
            if (i % 4 == 0) {
                ASSERT_TRUE(mapper.add_local_map(robot->maps[i / 4], session).added);
            }
            const KeyframeResult k = mapper.add_keyframe(robot->keyframe(i), session);
            for (const LoopRejection& j : k.rejected)
                held += j.reason.rfind("held: the first loop between session", 0) == 0;
            if (k.optimisation_due()) {
                ASSERT_TRUE(mapper.optimise().solved);
            }
        }
    }
    EXPECT_GE(held, 2u);
    for (const LoopClosure& l : mapper.loops())
        EXPECT_EQ(l.query_session, l.match_session) << "a loop between the robots was added";
    const OptimisationSummary o = mapper.optimise();
    ASSERT_TRUE(o.solved) << o.message;
    EXPECT_EQ(o.components, 2u);
    EXPECT_FALSE(mapper.session_status(s2).joined);
}

// Once two robots are placed together by loops, the graph says where the other's keyframes lie: a
// robot passing the other's place on another path (4 m aside, the other way), where no descriptor
// matches, still closes loops with the other's local maps there, verified from the graph's
// estimate. Robot 2 drives east along y = 0 from x = -9; robot 1 at the same time east along
// y = 0 from x = 0 (the same places, seen alike: the robots join), then back west along y = 4.
// The descriptors match identical views only here, so whatever closes the way back is a
// candidate by place.
TEST(MapperMultiRobot, ARobotPassingAnotherRobotsPlacesOnAnotherPathClosesLoopsByPlace) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(61));
    common::PoseList out_back, ahead;
    for (int i = 0; i < 16; ++i) out_back.push_back(registration::test::xy_yaw(3.0 * i, 0.0, 0.0));
    for (int i = 0; i < 16; ++i)
        out_back.push_back(registration::test::xy_yaw(45.0 - 3.0 * i, 4.0, 180.0));
    for (int i = 0; i < 16; ++i)
        ahead.push_back(registration::test::xy_yaw(-9.0 + 3.0 * i, 0.0, 0.0));
    const Route r1(scene, out_back, 100.0), r2(scene, ahead, 100.5);
    MapperConfig c = robots_config();
    c.loop_detection.max_distance = 1e-3;  // identical views only
    c.long_term.merge = false;             // robot 2's maps stay its own (not folded into 1's)
    Mapper mapper(c);
    const std::uint32_t s1 = mapper.open_session("robot1");
    const std::uint32_t s2 = mapper.open_session("robot2");
    for (std::size_t i = 0; i < r1.truth.size(); ++i) {
        for (const auto& [route, session] : {std::make_pair(&r2, s2), std::make_pair(&r1, s1)}) {
            if (i >= route->truth.size()) continue;
            if (i % 4 == 0) {
                ASSERT_TRUE(mapper.add_local_map(route->maps[i / 4], session).added);
            }
            const KeyframeResult k = mapper.add_keyframe(route->keyframe(i), session);
            ASSERT_TRUE(k.added) << k.message;
            if (k.optimisation_due()) {
                ASSERT_TRUE(mapper.optimise().solved);
            }
        }
    }
    ASSERT_TRUE(mapper.session_status(s2).joined) << mapper.session_status(s2).message;
    // Every local map of robot 1's way back is joined to one of robot 2's by a loop, each with
    // the true relative pose.
    std::set<std::uint64_t> joined;
    for (const LoopClosure& l : mapper.loops()) {
        if (l.query_session != s1 || l.match_session != s2 || l.query_scan < 16) continue;
        joined.insert(l.query_scan / 4);
        const Eigen::Isometry3d truth = r2.truth[l.match_scan].inverse() * r1.truth[l.query_scan];
        const Eigen::Isometry3d err = truth.inverse() * l.T_match_query;
        EXPECT_LT(err.translation().norm(), 0.05) << l.query_scan << " -> " << l.match_scan;
        EXPECT_LT(angle_deg(err), 0.3) << l.query_scan << " -> " << l.match_scan;
    }
    EXPECT_EQ(joined, (std::set<std::uint64_t>{4, 5, 6, 7}));
    const OptimisationSummary o = mapper.optimise();
    ASSERT_TRUE(o.solved) << o.message;
    for (std::size_t i = 16; i < r1.truth.size(); ++i) {
        const Eigen::Isometry3d err =
            r1.truth[i].inverse() * *mapper.T_world_lidar(i / 4, r1.odom[i], s1);
        EXPECT_LT(err.translation().norm(), 0.05) << "keyframe " << i;
    }
}

// Robot 2 maps another site (another scene) at the same time: no loop ties it to robot 1, it
// stays its own part of the graph at its own odometry's estimate, and says so.
TEST(MapperMultiRobot, ARobotThatNeverMeetsTheOtherStaysUnjoinedAndSaysSo) {
    const Robot r1(registration::test::with_dense_ground(registration::test::synthetic_scene(61)),
                   0.0, 0.0, false, 100.0);
    const Robot r2(registration::test::with_dense_ground(registration::test::synthetic_scene(7)),
                   45.0, 2.0, true, 100.5);
    Mapper mapper(robots_config());
    const std::uint32_t s1 = mapper.open_session("robot1");
    const std::uint32_t s2 = mapper.open_session("robot2");
    EXPECT_NE(mapper.session_status(s2).message.find("has no local map yet"), std::string::npos);
    interleave(r1, r2, s1, s2, mapper);
    for (const LoopClosure& l : mapper.loops())
        EXPECT_EQ(l.query_session, l.match_session) << "a loop between the two sites";
    const OptimisationSummary o = mapper.optimise();
    ASSERT_TRUE(o.solved) << o.message;
    EXPECT_EQ(o.components, 2u);
    EXPECT_EQ(mapper.placed_parts(), 2u);
    const SessionStatus st = mapper.session_status(s2);
    EXPECT_FALSE(st.joined);
    EXPECT_EQ(st.message,
              "session 1 (robot2) not joined to the map yet: its poses, corrected_odometry and "
              "map_to_odom are its own odometry's, from where it started");
    // Its poses are its odometry's: its odometry frame is not moved (its own loops, between maps
    // along its straight drive, agree with its odometry to millimetres).
    for (std::uint64_t m = 0; m < 4; ++m) {
        const Eigen::Isometry3d c = *mapper.T_world_odom(m, s2);
        EXPECT_LT(c.translation().norm(), 0.01) << "local map " << m;
        EXPECT_LT(angle_deg(c), 0.05) << "local map " << m;
    }
    ASSERT_EQ(mapper.segments(s2).size(), 1u);
    EXPECT_TRUE(mapper.session_status(s1).joined);
}

}  // namespace
}  // namespace ltm::mapping
