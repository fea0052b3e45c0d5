#include "common/core/pose_xyz_rpy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace ltm::common {
namespace {

TEST(PoseXyzRpy, AsRosStaticTransformPublisher) {
    const Eigen::Isometry3d T = pose_from_xyz_rpy({1.0, 2.0, 3.0, 90.0, 0.0, 0.0});
    EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
    // Roll 90 deg: y goes to z.
    EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
    // Fixed axes x, then y, then z: R = Rz(yaw) Ry(pitch) Rx(roll).
    const Eigen::Isometry3d R = pose_from_xyz_rpy({0, 0, 0, 90.0, 0.0, 90.0});
    EXPECT_TRUE((R.linear() * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
    EXPECT_TRUE((R.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
    EXPECT_THROW(pose_from_xyz_rpy({1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(pose_from_xyz_rpy({0, 0, NAN, 0, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace ltm::common
