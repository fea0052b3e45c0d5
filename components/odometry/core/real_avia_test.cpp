// Regression on real Livox data (issue 27 follow-up): the hku-avia session 1 keyframes, every 3rd
// (~1.1 s apart, a handheld narrow view), against the reference (FAST-LIO2). On main of
// 2026-11-28 the second scan restarted a segment (a 8.1 s pause is no kidnap) and fits the
// constant-velocity prediction disagreed with along a weakly constrained direction were replaced
// by that prediction (up to 1.4 m off a step; 11 of the first 30 scans not tracked). Needs
// /work/shared (skipped without it).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"
#include "common/core/trajectory_io.hpp"
#include "odometry/core/odometry.hpp"
#include "registration/core/se3.hpp"

namespace ltm::odometry {
namespace {

std::string avia_session(int session) {
    const std::string dir =
        LTM_SOURCE_DIR "/../shared/data/hku-avia-2session/session" + std::to_string(session);
    return std::filesystem::exists(dir + "/Scans/000090.pcd") ? dir : std::string();
}
std::string avia_session1() { return avia_session(1); }

TEST(RealAvia, EveryThirdKeyframeIsTrackedAlongItsWeakDirections) {
    const std::string dir = avia_session1();
    if (dir.empty()) GTEST_SKIP() << "hku-avia session1 not found under ../shared/data";
    const std::vector<double> times = common::read_times(dir + "/times.txt");
    const common::PoseList reference = common::read_kitti_poses(dir + "/odom_poses.txt");
    Odometry odo(preset_config(SensorPreset::kNarrow));
    constexpr int kScans = 30, kEvery = 3;
    Eigen::Isometry3d last_est = Eigen::Isometry3d::Identity();
    int registered = 0;
    double worst = 0.0;
    std::string worst_what;
    for (int i = 0; i < kScans; ++i) {
        const int k = kEvery * i;
        char name[32];
        std::snprintf(name, sizeof name, "/Scans/%06d.pcd", k);
        const FrameResult r = odo.register_frame(common::load_cloud_file(dir + name, times[k]));
        ASSERT_TRUE(r.pose_valid()) << i << ": " << r.message;
        EXPECT_NE(r.status, FrameStatus::kRestarted) << i << ": " << r.message;
        registered += r.registered();
        if (i > 0) {
            const Eigen::Isometry3d est = last_est.inverse() * r.T_odom_lidar;
            const Eigen::Isometry3d ref = reference[k - kEvery].inverse() * reference[k];
            const double err = (ref.inverse() * est).translation().norm();
            if (err > worst) {
                worst = err;
                worst_what = std::to_string(i) + " (" + r.search_used + "): " + r.message;
            }
        }
        last_est = r.T_odom_lidar;
    }
    EXPECT_LT(worst, 0.25) << "worst step error at scan " << worst_what;
    EXPECT_GE(registered, kScans - 4);
}

// Every 5th keyframe of session 2 (1-1.3 s apart, 26-45 deg turns): on main of 2026-11-28 scans
// 5 and 6 were reported degenerate "along a direction the registration could not observe" at
// positions 20 and 27 m off their step (a search probe had slid there; the position along that
// direction was the probe's, not the prediction's). Published poses, restarts included.
TEST(RealAvia, EveryFifthKeyframeNeverSlidesAlongAnUnobservedDirection) {
    const std::string dir = avia_session(2);
    if (dir.empty()) GTEST_SKIP() << "hku-avia session2 not found under ../shared/data";
    const std::vector<double> times = common::read_times(dir + "/times.txt");
    const common::PoseList reference = common::read_kitti_poses(dir + "/odom_poses.txt");
    Odometry odo(preset_config(SensorPreset::kNarrow));
    constexpr int kScans = 9, kEvery = 5;
    Eigen::Isometry3d last_est = Eigen::Isometry3d::Identity();
    for (int i = 0; i < kScans; ++i) {
        const int k = kEvery * i;
        char name[32];
        std::snprintf(name, sizeof name, "/Scans/%06d.pcd", k);
        const FrameResult r = odo.register_frame(common::load_cloud_file(dir + name, times[k]));
        ASSERT_TRUE(r.pose_valid()) << i << ": " << r.message;
        if (i > 0) {
            const Eigen::Isometry3d est = last_est.inverse() * r.T_odom_lidar;
            const Eigen::Isometry3d ref = reference[k - kEvery].inverse() * reference[k];
            EXPECT_LT((ref.inverse() * est).translation().norm(), 3.0)
                << "scan " << i << " (" << r.search_used << "): " << r.message;
        }
        last_est = r.T_odom_lidar;
    }
}

}  // namespace
}  // namespace ltm::odometry
