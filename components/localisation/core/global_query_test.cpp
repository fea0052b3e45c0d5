// Global localisation off the tracking thread (global_query.hpp, Localiser::set_global_elsewhere):
// the hand-over's rules and the carry forward, driven by hand (the test plays the other thread:
// it holds a request as long as it likes and answers it with a GlobalLocaliser of its own), so
// every order of events is deterministic.
#include "localisation/core/global_query.hpp"

#include <gtest/gtest.h>

#include "localisation/core/localiser.hpp"
#include "localisation/core/localiser_test_scene.hpp"

namespace ltm::localisation {
namespace {

using namespace test_scene;

TEST(GlobalHandOver, OneQueryAtATimeAndStaleAnswersAreDropped) {
    GlobalHandOver h;
    const std::vector<Eigen::Vector3f> points(3, Eigen::Vector3f::Ones());
    const auto r1 = h.ask(1.0, points, Eigen::Isometry3d::Identity(), 0, std::nullopt);
    ASSERT_TRUE(r1);
    EXPECT_EQ(r1->points.size(), 3u);
    EXPECT_TRUE(h.busy());
    EXPECT_DOUBLE_EQ(h.asked_stamp(), 1.0);
    // A newer scan asks nothing while the query is out.
    EXPECT_FALSE(h.ask(1.1, points, Eigen::Isometry3d::Identity(), 0, std::nullopt));
    GlobalAnswer a;
    a.id = r1->id;
    a.stamp = r1->stamp;
    a.segment = r1->segment;
    std::string why;
    // An answer to another query is not this one's.
    GlobalAnswer other = a;
    other.id = r1->id + 7;
    EXPECT_EQ(h.receive(other, 0, &why), GlobalHandOver::Fate::kUnknown);
    EXPECT_TRUE(h.busy());
    EXPECT_EQ(h.receive(a, 0, &why), GlobalHandOver::Fate::kApply) << why;
    EXPECT_FALSE(h.busy());
    EXPECT_EQ(h.receive(a, 0, &why), GlobalHandOver::Fate::kUnknown);  // once
    // The odometry restarted since the scan was asked: its frame is another.
    const auto r2 = h.ask(2.0, points, Eigen::Isometry3d::Identity(), 0, std::nullopt);
    ASSERT_TRUE(r2);
    a.id = r2->id;
    EXPECT_EQ(h.receive(a, 1, &why), GlobalHandOver::Fate::kStale);
    EXPECT_NE(why.find("restarted"), std::string::npos) << why;
    // An initial pose came since.
    const auto r3 = h.ask(3.0, points, Eigen::Isometry3d::Identity(), 1, std::nullopt);
    ASSERT_TRUE(r3);
    h.hint_changed();
    a.id = r3->id;
    a.segment = 1;
    EXPECT_EQ(h.receive(a, 1, &why), GlobalHandOver::Fate::kStale);
    EXPECT_NE(why.find("initial pose"), std::string::npos) << why;
    EXPECT_TRUE(h.ask(3.1, points, Eigen::Isometry3d::Identity(), 1, std::nullopt));
}

TEST(GlobalHandOver, AnAnswerIsCarriedForwardByTheOdometry) {
    GlobalAnswer a;
    a.T_odom_lidar = mt::xy_yaw(5.0, 1.0, 30.0);
    a.result.T_map_lidar = mt::xy_yaw(-20.0, 4.0, 100.0);
    // The robot moved 3 m ahead and turned 10 deg since, as the odometry saw it.
    const Eigen::Isometry3d motion = mt::xy_yaw(3.0, 0.0, 10.0);
    const Eigen::Isometry3d now = carry_forward(a, a.T_odom_lidar * motion);
    const Errors e = error_of(now, a.result.T_map_lidar * motion);
    EXPECT_LT(e.translation, 1e-9);
    EXPECT_LT(e.rotation_deg, 1e-6);
    const Eigen::Isometry3d T_map_odom = answer_T_map_odom(a);
    EXPECT_LT(error_of(T_map_odom * a.T_odom_lidar, a.result.T_map_lidar).translation, 1e-9);
}

// The localiser with its global queries elsewhere: no pose while the first query runs (never a
// guess reported as tracked), then the answer of the first scan carried to the scan of now.
TEST(LocaliserElsewhere, SearchesWithoutAPoseThenCarriesTheAnswerForward) {
    const SceneMap& s = scene_map();
    Localiser loc(s.map);
    loc.set_global_elsewhere(true);
    GlobalLocaliser other(s.map, loc.config().global);  // the other thread's
    const Eigen::Isometry3d T_odom_map = mt::xy_yaw(40.0, -7.0, 73.0);
    double stamp = 100.0;
    auto step = [&](int i) {
        const Eigen::Isometry3d truth = s.path[std::size_t(i)] * mt::xy_yaw(0.3, 0.4, 0.0);
        const LocalisationUpdate u = loc.process(stamp, mt::view(s.scene, truth, 60.0),
                                                 OdometryInput{T_odom_map * truth, 0});
        stamp += 0.1;
        return std::make_pair(u, truth);
    };
    auto [u0, t0] = step(2);
    EXPECT_EQ(u0.state, LocalisationState::kInitialising);
    EXPECT_FALSE(u0.pose_valid);
    EXPECT_TRUE(u0.global_asked);
    EXPECT_FALSE(u0.global_ran);
    std::optional<GlobalRequest> request = loc.take_request();
    ASSERT_TRUE(request);
    EXPECT_FALSE(loc.take_request());  // once
    EXPECT_TRUE(loc.global_busy());
    // Two scans while the query runs: searching, no pose, nothing more asked.
    for (int i = 3; i <= 4; ++i) {
        auto [u, t] = step(i);
        EXPECT_EQ(u.state, LocalisationState::kInitialising) << u.message;
        EXPECT_FALSE(u.pose_valid);
        EXPECT_FALSE(u.global_asked);
        EXPECT_NE(u.message.find("running"), std::string::npos) << u.message;
        EXPECT_FALSE(loc.take_request());
    }
    const GlobalAnswer a = answer(other, *request);
    ASSERT_TRUE(a.result.localised) << a.result.reason;
    EXPECT_LT(error_of(a.result.T_map_lidar, t0).translation, 0.1);
    loc.give_answer(a);
    // Applied to scan 5: its own pose (the first scan's answer carried 0.3 s forward), not scan
    // 2's.
    auto [u5, t5] = step(5);
    EXPECT_EQ(u5.state, LocalisationState::kRelocalised) << u5.message;
    ASSERT_TRUE(u5.pose_valid);
    EXPECT_TRUE(u5.global_ran);
    EXPECT_NEAR(u5.global_carried_s, 0.3, 1e-6);
    EXPECT_LT(error_of(u5.T_map_lidar, t5).translation, 0.1) << u5.message;
    EXPECT_GT(error_of(u5.T_map_lidar, t0).translation, 1.0);
    EXPECT_LT(error_of(u5.T_map_odom, T_odom_map.inverse()).translation, 0.1);
    EXPECT_FALSE(loc.global_busy());
    // Then tracking, no query.
    for (int i = 6; i <= 8; ++i) {
        auto [u, t] = step(i);
        EXPECT_EQ(u.state, LocalisationState::kTracking) << u.message;
        EXPECT_LT(error_of(u.T_map_lidar, t).translation, 0.1);
        EXPECT_FALSE(loc.take_request());
    }
}

// An odometry restart while tracking: the query is asked, tracking goes on from the last pose
// meanwhile; a query asked before the restart is answered in the old frame and dropped.
TEST(LocaliserElsewhere, TracksThroughARestartAndDropsAnAnswerOfTheOldFrame) {
    const SceneMap& s = scene_map();
    Localiser loc(s.map);
    loc.set_global_elsewhere(true);
    GlobalLocaliser other(s.map, loc.config().global);
    double stamp = 100.0;
    auto step = [&](const Eigen::Isometry3d& truth, std::uint32_t segment,
                    const Eigen::Isometry3d& T_odom_map) {
        const LocalisationUpdate u = loc.process(stamp, mt::view(s.scene, truth, 60.0),
                                                 OdometryInput{T_odom_map * truth, segment});
        stamp += 0.1;
        return u;
    };
    const Eigen::Isometry3d odom0 = mt::xy_yaw(10.0, 2.0, 20.0);
    step(s.path[3], 0, odom0);
    loc.give_answer(answer(other, *loc.take_request()));
    LocalisationUpdate u = step(s.path[4], 0, odom0);
    ASSERT_EQ(u.state, LocalisationState::kRelocalised) << u.message;
    // The robot stops at path[5]; the odometry restarts there in a new frame.
    u = step(s.path[5], 0, odom0);
    ASSERT_EQ(u.state, LocalisationState::kTracking) << u.message;
    const Eigen::Isometry3d odom1 = mt::xy_yaw(-3.0, 5.0, 40.0) * s.path[5].inverse();
    u = step(s.path[5], 1, odom1);
    EXPECT_TRUE(u.global_asked);
    EXPECT_EQ(u.state, LocalisationState::kTracking) << u.message;
    EXPECT_TRUE(u.pose_valid);
    EXPECT_LT(error_of(u.T_map_lidar, s.path[5]).translation, 0.1) << u.message;
    const std::optional<GlobalRequest> r1 = loc.take_request();
    ASSERT_TRUE(r1);
    EXPECT_EQ(r1->segment, 1u);
    // Its answer, applied while still tracking: relocalised on the scan of now.
    u = step(s.path[5], 1, odom1);
    loc.give_answer(answer(other, *r1));
    u = step(s.path[6], 1, odom1);
    EXPECT_EQ(u.state, LocalisationState::kRelocalised) << u.message;
    EXPECT_LT(error_of(u.T_map_lidar, s.path[6]).translation, 0.1) << u.message;
    // A gap asks a query in segment 1; the odometry restarts again before the answer: dropped.
    stamp += 2.0;
    const Eigen::Isometry3d odom2 = mt::xy_yaw(1.0, 1.0, -10.0);
    u = step(s.path[6], 1, odom1);
    EXPECT_TRUE(u.global_asked) << u.message;
    const std::optional<GlobalRequest> r2 = loc.take_request();
    ASSERT_TRUE(r2);
    u = step(s.path[6], 2, odom2);
    EXPECT_FALSE(u.global_asked);  // the first is still out
    loc.give_answer(answer(other, *r2));
    u = step(s.path[6], 2, odom2);
    EXPECT_NE(u.state, LocalisationState::kRelocalised) << u.message;
    EXPECT_TRUE(u.global_ran);
    EXPECT_TRUE(u.global_asked);  // again, in the new frame
    EXPECT_NE(u.message.find("restarted"), std::string::npos) << u.message;
    EXPECT_TRUE(u.pose_valid) << u.message;  // tracking went on in the new frame
    EXPECT_LT(error_of(u.T_map_lidar, s.path[6]).translation, 0.1) << u.message;
}

}  // namespace
}  // namespace ltm::localisation
