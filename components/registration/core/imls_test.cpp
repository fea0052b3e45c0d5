#include "registration/core/imls.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "registration/core/test_scenes.hpp"

namespace ltm::registration {
namespace {

using Eigen::Vector3d;
using Eigen::Vector3f;

// Eq. 3, 4, 6 evaluated directly: every voxel of the map, kept when inside the 3x3x3 block.
bool brute_force(const VoxelGrid& map, const Vector3f& x, const ImlsParams& p, double* distance,
                 Vector3d* projection) {
    Eigen::Vector3i vx;
    if (!voxel_coords(x, float(1.0 / map.voxel_size()), &vx)) return false;
    const Vector3d xd = x.cast<double>();
    std::vector<std::uint32_t> block;
    double best = 1e300;
    std::uint32_t nearest = 0;
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        const Surfel& s = map.surfels()[i];
        if (!s.usable || (unpack_key(map.keys()[i]) - vx).cwiseAbs().maxCoeff() > 1) continue;
        block.push_back(i);
        const double d = (xd - s.centre.cast<double>()).norm();
        if (d < best) {
            best = d;
            nearest = i;
        }
    }
    if (block.empty() || best >= p.max_distance) return false;
    const Vector3d nx = map.surfels()[nearest].normal.cast<double>();
    double num = 0.0, den = 0.0;
    for (const std::uint32_t i : block) {
        const Vector3d c = map.surfels()[i].centre.cast<double>();
        Vector3d n = map.surfels()[i].normal.cast<double>();
        if (n.dot(nx) < 0.0) n = -n;
        const double w = std::exp(-(xd - c).squaredNorm() / (p.bandwidth * p.bandwidth));
        num += w * (xd - c).dot(n);
        den += w;
    }
    *distance = num / den;
    *projection = xd - *distance * nx;
    return true;
}

VoxelGrid room_map(double voxel) {
    const test::Scene scene = test::room_scene();
    const auto pose = test::make_pose(1, 2, 1.5, 0, 0, 0);
    test::ScanPattern pattern;
    pattern.rings = 64;
    pattern.azimuths = 1800;
    const auto cloud = test::scan_scene(scene, pattern, pose, pose, 1);
    VoxelGrid map(voxel, VoxelConfig{});
    std::vector<Vector3f> world;
    for (const auto& p : cloud.points) world.push_back((pose * p.cast<double>()).cast<float>());
    map.integrate(world, pose.translation().cast<float>(), 0.0,
                  [](const Eigen::Vector3f&) { return true; });
    return map;
}

TEST(Imls, MatchesBruteForceNearSurfaces) {
    const VoxelGrid map = room_map(0.5);
    ASSERT_GT(map.usable_voxels(), 500u);
    ImlsParams params;
    params.bandwidth = 0.5f;
    params.max_distance = 1.0f;
    std::mt19937 rng(5);
    std::uniform_int_distribution<std::size_t> pick(0, map.size() - 1);
    std::normal_distribution<float> off(0.0f, 0.3f);
    int compared = 0, agreed_missing = 0;
    for (int q = 0; q < 2000; ++q) {
        const Vector3f x = map.surfels()[pick(rng)].centre + Vector3f(off(rng), off(rng), off(rng));
        ImlsResult r;
        double want = 0.0;
        Vector3d want_y = Vector3d::Zero();
        const bool got = imls_distance(map, x, params, &r);
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
    const VoxelGrid map = room_map(1.0);
    ImlsParams params;
    // Above the floor (z = 0), away from walls and boxes: distance = height, projection on floor.
    for (const float h : {-0.3f, 0.1f, 0.4f}) {
        ImlsResult r;
        ASSERT_TRUE(imls_distance(map, Vector3f(0.3f, -2.2f, h), params, &r));
        EXPECT_NEAR(std::abs(r.distance), std::abs(h), 0.02f);
        EXPECT_NEAR(r.projection.z(), 0.0f, 0.02f);
        EXPECT_GT(std::abs(r.normal.z()), 0.999f);
    }
    ImlsResult r;
    EXPECT_FALSE(imls_distance(map, Vector3f(0.0f, 0.0f, 4.0f), params, &r));  // in free space
}

}  // namespace
}  // namespace ltm::registration
