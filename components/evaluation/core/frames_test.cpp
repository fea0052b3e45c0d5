#include "evaluation/core/frames.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

// KITTI-like Tr = T_cam_lidar: lidar x (forward) -> camera z, lidar y (left) -> camera -x,
// lidar z (up) -> camera -y.
Eigen::Isometry3d kitti_like_tr() {
    Eigen::Isometry3d Tr = Eigen::Isometry3d::Identity();
    Tr.linear() << 0, -1, 0, 0, 0, -1, 1, 0, 0;
    return Tr;
}

TEST(Frames, CameraForwardIsLidarForward) {
    Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
    P.translation() = Eigen::Vector3d(0, 0, 2);  // camera moved 2 m along its z (forward)
    const common::PoseList lidar = camera_to_lidar({P}, kitti_like_tr());
    EXPECT_TRUE(lidar[0].translation().isApprox(Eigen::Vector3d(2, 0, 0)));
    EXPECT_TRUE(lidar[0].linear().isApprox(Eigen::Matrix3d::Identity()));
}

TEST(Frames, LidarToCameraInvertsCameraToLidar) {
    Eigen::Isometry3d Tr = kitti_like_tr();
    Tr.translation() = Eigen::Vector3d(0.1, -0.2, 0.3);
    Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
    P.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 1, 0.1).normalized()).matrix();
    P.translation() = Eigen::Vector3d(1, 2, 3);
    const common::PoseList back = lidar_to_camera(camera_to_lidar({P}, Tr), Tr);
    EXPECT_TRUE(back[0].matrix().isApprox(P.matrix(), 1e-12));
}

common::Trajectory stamped(const std::vector<double>& stamps) {
    common::Trajectory t;
    for (double s : stamps) {
        common::StampedPose p;
        p.stamp = s;
        p.pose.translation() = Eigen::Vector3d(s, 0, 0);
        t.push_back(p);
    }
    return t;
}

TEST(Frames, PairsByNearestStampWithinTolerance) {
    const auto ref = stamped({0.3, 0.0, 0.1, 0.2});  // unsorted on purpose
    const PairedPoses p = pair_by_stamp(stamped({0.101, 0.19, 0.5}), ref, 0.02);
    ASSERT_EQ(p.estimate.size(), 2u);
    EXPECT_EQ(p.unmatched, 1u);
    EXPECT_DOUBLE_EQ(p.reference[0].translation().x(), 0.1);
    EXPECT_DOUBLE_EQ(p.reference[1].translation().x(), 0.2);
}

TEST(Frames, UsesEachReferencePoseOnce) {
    const PairedPoses p = pair_by_stamp(stamped({0.1, 0.105}), stamped({0.0, 0.1, 0.2}), 0.02);
    EXPECT_EQ(p.estimate.size(), 1u);
    EXPECT_EQ(p.unmatched, 1u);
}

}  // namespace
}  // namespace ltm::eval
