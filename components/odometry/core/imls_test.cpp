#include "odometry/core/imls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "odometry/core/local_map.hpp"
#include "odometry/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

using Eigen::Vector3d;
using Eigen::Vector3f;

// Eq. 3, 4, 6 evaluated directly: every voxel of the map, kept when inside the 3x3x3 block.
bool brute_force(const LocalMap& map, const Vector3f& x, const ImlsParams& p, double* distance,
                 Vector3d* projection) {
    Eigen::Vector3i vx;
    if (!voxel_coords(x, float(1.0 / map.voxel_size()), &vx)) return false;
    const Vector3d xd = x.cast<double>();
    std::vector<std::uint32_t> block;
    double best = 1e300;
    std::uint32_t nearest = 0;
    for (std::uint32_t i = 0; i < map.voxels().size(); ++i) {
        const Surfel& s = map.voxels().surfels()[i];
        if (!s.usable || (unpack_key(map.voxels().keys()[i]) - vx).cwiseAbs().maxCoeff() > 1)
            continue;
        block.push_back(i);
        const double d = (xd - s.centre.cast<double>()).norm();
        if (d < best) {
            best = d;
            nearest = i;
        }
    }
    if (block.empty() || best >= p.max_distance) return false;
    const Vector3d nx = map.voxels().surfels()[nearest].normal.cast<double>();
    double num = 0.0, den = 0.0;
    for (const std::uint32_t i : block) {
        const Vector3d c = map.voxels().surfels()[i].centre.cast<double>();
        Vector3d n = map.voxels().surfels()[i].normal.cast<double>();
        if (n.dot(nx) < 0.0) n = -n;
        const double w = std::exp(-(xd - c).squaredNorm() / (p.bandwidth * p.bandwidth));
        num += w * (xd - c).dot(n);
        den += w;
    }
    *distance = num / den;
    *projection = xd - *distance * nx;
    return true;
}

LocalMap room_map(double voxel) {
    const test::Scene scene = test::room_scene();
    const auto pose = test::make_pose(1, 2, 1.5, 0, 0, 0);
    test::ScanPattern pattern;
    pattern.rings = 64;
    pattern.azimuths = 1800;
    const auto cloud = test::scan_scene(scene, pattern, pose, pose, 1);
    LocalMap map(0, Eigen::Isometry3d::Identity(), voxel, 50.0, VoxelConfig{}, 0.0);
    std::vector<Vector3f> world;
    for (const auto& p : cloud.points) world.push_back((pose * p.cast<double>()).cast<float>());
    map.integrate(world, pose.translation().cast<float>(), 0.0);
    return map;
}

TEST(Imls, MatchesBruteForceNearSurfaces) {
    const LocalMap map = room_map(0.5);
    ASSERT_GT(map.voxels().usable_voxels(), 500u);
    ImlsParams params;
    params.bandwidth = 0.5f;
    params.max_distance = 1.0f;
    std::mt19937 rng(5);
    std::uniform_int_distribution<std::size_t> pick(0, map.voxels().size() - 1);
    std::normal_distribution<float> off(0.0f, 0.3f);
    int compared = 0, agreed_missing = 0;
    for (int q = 0; q < 2000; ++q) {
        const Vector3f x =
            map.voxels().surfels()[pick(rng)].centre + Vector3f(off(rng), off(rng), off(rng));
        ImlsResult r;
        double want = 0.0;
        Vector3d want_y = Vector3d::Zero();
        const bool got = imls_distance(map.voxels(), x, params, &r);
        const bool expected = brute_force(map, x, params, &want, &want_y);
        ASSERT_EQ(got, expected) << "query " << x.transpose();
        if (!got) {
            ++agreed_missing;
            continue;
        }
        ++compared;
        EXPECT_NEAR(r.distance, want, 1e-4);
        EXPECT_LT((r.projection.cast<double>() - want_y).norm(), 1e-4);
        EXPECT_NEAR(r.normal.norm(), 1.0f, 1e-5f);
        EXPECT_NEAR(r.normal.dot(x - r.projection), r.distance, 1e-4f);
    }
    EXPECT_GT(compared, 1500);
    EXPECT_GT(agreed_missing, 0);
}

TEST(Imls, FlatPlaneGivesTheSignedDistanceAndProjectsOntoIt) {
    const LocalMap map = room_map(1.0);
    ImlsParams params;
    // Above the floor (z = 0), away from walls and boxes: distance = height, projection on floor.
    for (const float h : {-0.3f, 0.1f, 0.4f}) {
        ImlsResult r;
        ASSERT_TRUE(imls_distance(map.voxels(), Vector3f(0.3f, -2.2f, h), params, &r));
        EXPECT_NEAR(std::abs(r.distance), std::abs(h), 0.02f);
        EXPECT_NEAR(r.projection.z(), 0.0f, 0.02f);
        EXPECT_GT(std::abs(r.normal.z()), 0.999f);
    }
    ImlsResult r;
    EXPECT_FALSE(
        imls_distance(map.voxels(), Vector3f(0.0f, 0.0f, 4.0f), params, &r));  // in free space
}

}  // namespace
}  // namespace ltm::odometry
