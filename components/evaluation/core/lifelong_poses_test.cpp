#include "evaluation/core/lifelong_poses.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

common::StampedPose at(double stamp, double x, double y) {
    common::StampedPose p;
    p.stamp = stamp;
    p.pose.setIdentity();
    p.pose.translation() = Eigen::Vector3d(x, y, 0.0);
    return p;
}

// A square-ish path of 40 scans at 10 Hz in the world.
common::Trajectory truth_path() {
    common::Trajectory t;
    for (int i = 0; i < 40; ++i) t.push_back(at(100.0 + 0.1 * i, i * 0.5, (i % 10) * 0.3));
    return t;
}

Eigen::Isometry3d T_map_world() {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(5.0, -3.0, 1.0);
    return T;
}

TEST(LifelongPoses, AlignmentFromKeyframesRecoversTheMapFrame) {
    const common::Trajectory truth = truth_path();
    common::Trajectory keyframes;  // every 5th scan, in the map frame
    for (std::size_t i = 0; i < truth.size(); i += 5) {
        common::StampedPose k = truth[i];
        k.pose = T_map_world() * k.pose;
        k.stamp += 0.001;  // within max_dt
        keyframes.push_back(k);
    }
    const MapAlignment a = fit_map_alignment(keyframes, truth);
    EXPECT_EQ(a.matched, 8u);
    EXPECT_LT(a.ate.rmse, 1e-9);
    EXPECT_TRUE(a.T_world_map.isApprox(T_map_world().inverse(), 1e-9));
}

TEST(LifelongPoses, SimilarityTellsTheMapsScaleFromItsShape) {
    // A map 0.5 % short of the truth (an odometry that measures distances short): its keyframes
    // close every loop, and no rigid alignment fits them; the similarity fit finds the scale,
    // and a day's poses scored in it are right.
    const common::Trajectory truth = truth_path();
    const double short_by = 0.995;
    common::Trajectory keyframes;
    for (std::size_t i = 0; i < truth.size(); i += 2) {
        common::StampedPose k = truth[i];
        k.pose.translation() *= short_by;
        k.pose = T_map_world() * k.pose;
        keyframes.push_back(k);
    }
    const MapAlignment rigid = fit_map_alignment(keyframes, truth);
    EXPECT_GT(rigid.ate.rmse, 0.01);
    const MapSimilarity sim = fit_map_similarity(keyframes, truth);
    EXPECT_EQ(sim.matched, 20u);
    EXPECT_NEAR(sim.scale, 1.0 / short_by, 1e-9);
    EXPECT_LT(sim.rmse, 1e-9);
    const DayPoseScore in_sim =
        score_day_poses(scaled_positions(keyframes, sim.scale), truth, sim.T_world_map, {});
    EXPECT_EQ(in_sim.with_pose, 20u);
    EXPECT_LT(in_sim.max, 1e-9);
    const DayPoseScore in_rigid = score_day_poses(keyframes, truth, rigid.T_world_map, {});
    EXPECT_GT(in_rigid.max, 0.01);
}

TEST(LifelongPoses, CountsPosesErrorsAndKidnapRecovery) {
    const common::Trajectory truth = truth_path();
    const Eigen::Isometry3d T_world_map = T_map_world().inverse();
    common::Trajectory published;
    // Scans 0-9 right; 10-19 none (lost after a kidnap at scan 10); 20-21 wrong by 2 m; 22-39
    // right but 30 is 0.3 m off.
    for (int i = 0; i < 40; ++i) {
        if (i >= 10 && i < 20) continue;
        common::StampedPose p = truth[static_cast<std::size_t>(i)];
        if (i == 20 || i == 21) p.pose.translation().x() += 2.0;
        if (i == 30) p.pose.translation().y() += 0.3;
        p.pose = T_map_world() * p.pose;
        published.push_back(p);
    }
    published.push_back(published.front());  // a second pose for scan 0 is ignored
    const DayPoseScore s = score_day_poses(published, truth, T_world_map, {truth[10].stamp});
    EXPECT_EQ(s.scans, 40u);
    EXPECT_EQ(s.with_pose, 30u);
    EXPECT_EQ(s.wrong, 2u);
    EXPECT_NEAR(s.max, 2.0, 1e-9);
    EXPECT_NEAR(s.rmse, std::sqrt((4.0 + 4.0 + 0.09) / 30.0), 1e-9);
    EXPECT_LT(s.error[12], 0.0);
    ASSERT_EQ(s.kidnaps.size(), 1u);
    EXPECT_TRUE(s.kidnaps[0].recovered);
    EXPECT_NEAR(s.kidnaps[0].time_s, 1.2, 1e-9);  // scan 22
    EXPECT_EQ(s.kidnaps[0].scans, 12u);
    EXPECT_EQ(s.kidnaps[0].wrong, 2u);
}

TEST(LifelongPoses, KidnapNeverRecoveredAndNoPoses) {
    const common::Trajectory truth = truth_path();
    const DayPoseScore s =
        score_day_poses({}, truth, Eigen::Isometry3d::Identity(), {truth[5].stamp});
    EXPECT_EQ(s.with_pose, 0u);
    EXPECT_EQ(s.rmse, 0.0);
    ASSERT_EQ(s.kidnaps.size(), 1u);
    EXPECT_FALSE(s.kidnaps[0].recovered);
}

TEST(LifelongPoses, PosesWithStampsOfNoScanAreNotCounted) {
    const common::Trajectory truth = truth_path();
    common::Trajectory published{at(50.0, 0, 0), at(100.05, 0, 0)};  // between two scans
    const DayPoseScore s = score_day_poses(published, truth, Eigen::Isometry3d::Identity(), {});
    EXPECT_EQ(s.with_pose, 0u);
}

}  // namespace
}  // namespace ltm::eval
