#include "odometry/core/local_map.hpp"

#include <gtest/gtest.h>

#include <random>

#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Vector3f;

std::vector<Vector3f> random_points(int n, float half, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-half, half);
    std::vector<Vector3f> pts;
    for (int i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng), 0.3f * u(rng));
    return pts;
}

TEST(LocalMap, OriginIsTheAnchorSnappedToTheLattice) {
    const auto anchor = registration::test::make_pose(10.3, -4.7, 1.2, 0, 0, 30);
    LocalMap map(3, anchor, 0.5, 20.0, VoxelConfig{}, 7.0);
    EXPECT_EQ(map.id(), 3u);
    EXPECT_TRUE(map.origin().isApprox(Eigen::Vector3d(10.5, -4.5, 1.0)));
    EXPECT_TRUE(map.contains(Vector3f(-0.2f + 19.9f, 0.2f, 0.0f)));
    EXPECT_FALSE(map.contains(Vector3f(-0.2f + 20.1f, 0.2f, 0.0f)));
}

TEST(LocalMap, IntegratesOnlyInsideTheBoxIntoBothGrids) {
    LocalMap map(0, Eigen::Isometry3d::Identity(), 0.5, 8.0, VoxelConfig{}, 0.0, 4);
    ASSERT_NE(map.coarse(), nullptr);
    EXPECT_DOUBLE_EQ(map.coarse()->voxel_size(), 2.0);
    const auto pts = random_points(3000, 10.0f, 1);
    std::size_t inside = 0;
    for (const auto& p : pts) inside += map.contains(p);
    EXPECT_LT(inside, pts.size());
    EXPECT_EQ(map.integrate(pts, Vector3f(0, 0, 5), 1.0), inside);
    for (const registration::VoxelGrid* g : {&map.voxels(), map.coarse()}) {
        float weight = 0.0f;
        for (const auto& r : g->records()) weight += r.sums.weight;
        EXPECT_FLOAT_EQ(weight, float(inside));
    }
    EXPECT_EQ(map.scans_integrated(), 1u);
    EXPECT_EQ(map.last_update(), 1.0);
    LocalMap plain(1, Eigen::Isometry3d::Identity(), 0.5, 8.0, VoxelConfig{}, 0.0);
    EXPECT_EQ(plain.coarse(), nullptr);
}

TEST(LocalMap, SeedCopiesTheVoxelsInsideTheNewBox) {
    LocalMap a(0, Eigen::Isometry3d::Identity(), 1.0, 10.0, VoxelConfig{}, 0.0);
    a.integrate(random_points(4000, 9.0f, 4), Vector3f(0, 0, 5), 1.0);
    LocalMap b(1, registration::test::make_pose(6.2, 0.0, 0.0, 0, 0, 0), 1.0, 5.0, VoxelConfig{},
               2.0);
    b.seed_from(a);
    ASSERT_GT(b.voxels().size(), 0u);
    const Eigen::Vector3f shift = (b.origin() - a.origin()).cast<float>();
    std::size_t expected = 0;
    for (std::uint32_t i = 0; i < a.voxels().size(); ++i) {
        const Vector3f c_in_b = a.voxels().cell_centre(a.voxels().keys()[i]) - shift;
        if (!b.contains(c_in_b)) continue;
        ++expected;
        Eigen::Vector3i v;
        ASSERT_TRUE(registration::voxel_coords(c_in_b, 1.0f, &v));
        const std::uint32_t j = b.voxels().find(v);
        ASSERT_NE(j, registration::VoxelHash::kNone);
        EXPECT_LT((b.voxels().surfels()[j].centre + shift - a.voxels().surfels()[i].centre).norm(),
                  1e-4f);
        EXPECT_EQ(b.voxels().surfels()[j].normal, a.voxels().surfels()[i].normal);
        EXPECT_EQ(b.voxels().records()[j].sums.weight, a.voxels().records()[i].sums.weight);
        EXPECT_EQ(b.voxels().records()[j].created, a.voxels().records()[i].created);
    }
    EXPECT_EQ(b.voxels().size(), expected);
}

}  // namespace
}  // namespace ltm::odometry
