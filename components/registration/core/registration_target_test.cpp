#include "registration/core/registration_target.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "registration/core/loop_verifier.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::registration {
namespace {

double rot_deg(const Eigen::Isometry3d& T) {
    return Eigen::AngleAxisd(T.linear()).angle() * 180.0 / M_PI;
}

TEST(RegistrationTarget, LoadedMapReproducesTheVoxelsAndTheRegistration) {
    const std::vector<Eigen::Vector3f> scene = test::synthetic_scene(21);
    common::PoseList poses;
    std::vector<std::vector<Eigen::Vector3f>> scans;
    for (int i = 0; i < 5; ++i) {
        poses.push_back(test::xy_yaw(2.0 * i, 0.3 * i, 10.0 * i));
        scans.push_back(test::view(scene, poses.back(), 50.0));
    }
    const Eigen::Isometry3d anchor = test::xy_yaw(0.37, -0.21, 33.0);  // not on the lattice
    const common::LocalMapData data = test::build_local_map(5, anchor, scans, poses, 1.0, 40.0);
    ASSERT_GT(data.voxels.size(), 1000u);
    const RegistrationTarget t = make_registration_target(data, 0.4, 3);
    EXPECT_EQ(t.skipped_voxels, 0u);
    EXPECT_EQ(t.fine.size(), data.voxels.size());
    ASSERT_TRUE(t.coarse.has_value());
    EXPECT_GT(t.coarse->usable_voxels(), 50u);
    // Every voxel comes back exactly: centre, normal, planarity, stability, life.
    std::size_t usable = 0;
    for (const common::VoxelData& v : data.voxels) {
        if (!(v.planarity >= 0.4f) || v.normal.squaredNorm() == 0.0f) continue;
        ++usable;
        const std::uint32_t i = t.fine.find(v.index);
        ASSERT_NE(i, registration::VoxelHash::kNone);
        const registration::Surfel& s = t.fine.surfels()[i];
        EXPECT_EQ(s.centre, v.centre);
        EXPECT_LT((s.normal - v.normal).norm(), 1e-6f);
        EXPECT_EQ(s.planarity, v.planarity);
        EXPECT_EQ(s.stability, v.stability);
        EXPECT_TRUE(s.usable);
        EXPECT_EQ(t.fine.records()[i].observations, v.life.observations);
        EXPECT_EQ(t.fine.records()[i].created, v.life.created);
    }
    EXPECT_EQ(t.fine.usable_voxels(), usable);
    EXPECT_GT(usable, 500u);

    // Registering a new view against the rebuilt map lands where the scene says.
    const Eigen::Isometry3d truth = test::xy_yaw(5.0, 1.0, 25.0);
    const std::vector<Eigen::Vector3f> scan = test::view(scene, truth, 50.0);
    LoopVerifierConfig cfg;
    LoopVerifier verifier(cfg);
    const Eigen::Isometry3d T_anchor_truth = anchor.inverse() * truth;
    const LoopVerification v =
        verifier.verify(scan, 5, data, T_anchor_truth * test::xy_yaw(0.8, -0.6, 4.0));
    EXPECT_TRUE(v.accepted) << v.reason;
    const Eigen::Isometry3d err = T_anchor_truth.inverse() * v.T_anchor_lidar;
    EXPECT_LT(err.translation().norm(), 0.05);
    EXPECT_LT(rot_deg(err), 0.3);
}

}  // namespace
}  // namespace ltm::registration
