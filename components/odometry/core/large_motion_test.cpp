// Tracking through large motions between scans and recovery when nothing fits (issue: odometry
// that never stays lost): the search beyond the prediction, and the restart in a new segment.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <string>

#include "common/core/pcl_cloud_io.hpp"
#include "odometry/core/local_map_export.hpp"
#include "odometry/core/odometry.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Isometry3d;
constexpr double kRadToDeg = 180.0 / M_PI;

void expect_near_pose(const Isometry3d& est, const Isometry3d& truth, double t_tol,
                      double r_tol_deg, const std::string& what) {
    const Isometry3d d = truth.inverse() * est;
    EXPECT_LT(d.translation().norm(), t_tol) << what;
    EXPECT_LT(registration::rotation_angle(d) * kRadToDeg, r_tol_deg) << what;
}

Isometry3d read_matrix4(const std::string& path) {
    std::ifstream in(path);
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) in >> m(r, c);
    EXPECT_TRUE(bool(in)) << path;
    Isometry3d T;
    T.matrix() = m;
    return T;
}

// The real pair: the target starts the map at the origin, the source comes 1 s later with the
// odometry predicting no motion, while its points are moved so that the truth is the reference
// registration composed with an offset the prediction knows nothing about.
class RealPair : public testing::Test {
  protected:
    void SetUp() override {
        const std::string dir = LTM_SOURCE_DIR "/components/registration/core/testdata/";
        source_ = common::load_cloud_file(dir + "regpair_source.ply");
        target_ = common::load_cloud_file(dir + "regpair_target.ply");
        reference_ = read_matrix4(dir + "regpair_T_target_source.txt");
    }
    // Registers the source with its points expressed in frame `offset` of the true source frame;
    // the truth is then reference * offset.
    FrameResult register_offset(const Isometry3d& offset) {
        Odometry odo(OdometryConfig{});
        common::PointCloud t = target_;
        t.stamp = 0.0;
        EXPECT_EQ(odo.register_frame(t).status, FrameStatus::kInitialised);
        common::PointCloud s = source_;
        s.stamp = 1.0;
        const Eigen::Affine3f to_offset = offset.inverse().cast<float>();
        for (Eigen::Vector3f& p : s.points) p = to_offset * p;
        return odo.register_frame(s);
    }
    common::PointCloud source_, target_;
    Isometry3d reference_;
};

TEST_F(RealPair, RegisteredFromA30DegYawError) {
    for (const double yaw : {30.0, -30.0}) {
        const Isometry3d offset(Eigen::AngleAxisd(yaw / kRadToDeg, Eigen::Vector3d::UnitZ()));
        const FrameResult r = register_offset(offset);
        ASSERT_EQ(r.status, FrameStatus::kTracked) << yaw << ": " << r.message;
        // The reference is ICP quality (see the registration's own test); the odometry's coarser
        // settings end within a few tenths of a degree of it.
        expect_near_pose(r.T_odom_lidar, reference_ * offset, 0.05, 0.5,
                         "yaw " + std::to_string(yaw));
    }
}

TEST_F(RealPair, RegisteredFrom2MetresOff) {
    for (const Eigen::Vector3d& d :
         {Eigen::Vector3d(2.0, 0.0, 0.0), Eigen::Vector3d(0.0, -2.0, 0.0)}) {
        const Isometry3d offset = Isometry3d(Eigen::Translation3d(d));
        const FrameResult r = register_offset(offset);
        ASSERT_EQ(r.status, FrameStatus::kTracked) << d.transpose() << ": " << r.message;
        expect_near_pose(r.T_odom_lidar, reference_ * offset, 0.05, 0.5, "2 m off");
    }
}

// A 90 deg turn between two scans 1 s apart (the constant-velocity prediction says straight on).
TEST(LargeMotion, NinetyDegreeTurnBetweenTwoScansIsTracked) {
    const registration::test::Scene scene = registration::test::room_scene();
    registration::test::ScanPattern pattern;
    const Isometry3d poses[] = {
        registration::test::make_pose(-6.0, 1.0, 1.5, 0, 0, 0),
        registration::test::make_pose(-5.5, 1.0, 1.5, 0, 0, 0),
        registration::test::make_pose(-5.0, 1.2, 1.5, 0, 0, 90),
        registration::test::make_pose(-5.0, 1.7, 1.5, 0, 0, 90),
    };
    for (const double sign : {1.0, -1.0}) {
        Odometry odo(OdometryConfig{}, poses[0]);
        for (int i = 0; i < 4; ++i) {
            Isometry3d truth = poses[i];
            if (sign < 0 && i >= 2) {
                truth.linear() = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
            }
            common::PointCloud c =
                registration::test::scan_scene(scene, pattern, truth, truth, 3 + i);
            c.stamp = 1.0 * i;
            const FrameResult r = odo.register_frame(c);
            ASSERT_TRUE(r.registered() || i == 0) << i << ": " << r.message;
            expect_near_pose(r.T_odom_lidar, truth, 0.05, 0.5,
                             "scan " + std::to_string(i) + " (" + to_string(r.status) +
                                 ", overlap " + std::to_string(r.overlap) + ", inliers " +
                                 std::to_string(r.inliers) + ", searched " +
                                 std::to_string(r.searched) + ")");
        }
    }
}

// Nothing for 1 s, then the sensor is somewhere its map cannot explain (carried from the street
// into a clearing): the odometry ends its maps (handed over intact, segment 0) and restarts in
// segment 1 at its prediction, where the following scans track.
TEST(LargeMotion, LostTooLongRestartsInANewSegmentAndTracksOn) {
    const registration::test::Scene scene = registration::test::street_scene();
    registration::test::ScanPattern pattern;
    auto street = [](double x, double yaw) {
        return registration::test::make_pose(x, 0.0, 1.8, 0, 0, yaw);
    };
    auto scan = [&](const Isometry3d& pose, double stamp, int seed) {
        common::PointCloud c = registration::test::scan_scene(scene, pattern, pose, pose, seed);
        c.stamp = stamp;
        return c;
    };
    Odometry odo(OdometryConfig{}, street(0.0, 0.0));
    for (int i = 0; i < 4; ++i)
        ASSERT_TRUE(odo.register_frame(scan(street(i, 0), 0.1 * i, i)).registered() || i == 0);
    const std::size_t voxels = odo.active_local_maps().back().voxels().size();
    common::PointCloud empty;
    for (int k = 1; k <= 10; ++k) {
        empty.stamp = 0.3 + 0.1 * k;
        const FrameResult r = odo.register_frame(empty);
        EXPECT_EQ(r.status, FrameStatus::kSkippedTooFewPoints);
        EXPECT_NEAR(r.lost_for, 0.1 * k, 1e-9);
    }
    EXPECT_TRUE(odo.lost());
    // Tilted panels scattered in a clearing without ground: nothing the street's ground, walls
    // and poles can explain.
    registration::test::Scene hall;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int k = 0; k < 400; ++k) {
        const Eigen::Vector3d c(25.0 * u(rng), 25.0 * u(rng), 2.0 + 1.5 * u(rng));
        if (c.head<2>().norm() < 4.0) continue;
        const Eigen::Vector3d a = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
        const Eigen::Vector3d b = a.cross(Eigen::Vector3d(u(rng), u(rng), u(rng))).normalized();
        hall.add_quad(c, (0.8 + 0.5 * u(rng)) * a, (0.8 + 0.5 * u(rng)) * b);
    }
    auto in_hall = [&](const Isometry3d& pose, double stamp, int seed) {
        common::PointCloud c = registration::test::scan_scene(hall, pattern, pose, pose, seed);
        c.stamp = stamp;
        return c;
    };
    const Isometry3d restart_truth = registration::test::make_pose(-6.0, 1.0, 1.5, 0, 0, 0);
    const FrameResult restart = odo.register_frame(in_hall(restart_truth, 1.4, 20));
    ASSERT_EQ(restart.status, FrameStatus::kRestarted)
        << restart.message << " overlap " << restart.overlap << " inliers " << restart.inliers
        << " fraction " << restart.inlier_fraction << " searched " << restart.searched;
    EXPECT_TRUE(restart.pose_valid());
    EXPECT_FALSE(odo.lost());
    EXPECT_EQ(restart.segment, 1u);
    EXPECT_TRUE(restart.new_local_map);
    EXPECT_TRUE(restart.keyframe.has_value());  // loop detection can place it at once
    EXPECT_NE(restart.message.find("segment 1"), std::string::npos) << restart.message;
    // The old map is handed over whole, in segment 0; the new one is segment 1.
    const std::vector<LocalMap> finished = odo.take_finished_local_maps();
    ASSERT_EQ(finished.size(), 1u);
    EXPECT_EQ(finished[0].segment(), 0u);
    EXPECT_EQ(finished[0].voxels().size(), voxels);
    EXPECT_EQ(to_local_map_data(finished[0], 1, true, {}).segment, 0u);
    ASSERT_EQ(odo.active_local_maps().size(), 1u);
    EXPECT_EQ(odo.active_local_maps().back().segment(), 1u);
    EXPECT_EQ(to_local_map_data(odo.active_local_maps().back(), 1, false, {}).segment, 1u);
    // The following scans track in the new segment: their motion relative to the restart scan is
    // the true one.
    for (int i = 1; i <= 3; ++i) {
        const Isometry3d truth =
            restart_truth * registration::test::make_pose(0.5 * i, 0, 0, 0, 0, 5.0 * i);
        const FrameResult r = odo.register_frame(in_hall(truth, 1.4 + 0.1 * i, 20 + i));
        ASSERT_EQ(r.status, FrameStatus::kTracked) << i << ": " << r.message;
        EXPECT_EQ(r.segment, 1u);
        expect_near_pose(restart.T_odom_lidar.inverse() * r.T_odom_lidar,
                         restart_truth.inverse() * truth, 0.05, 0.3, "after the restart");
    }
}

}  // namespace
}  // namespace ltm::odometry
