#include "registration/core/voxel.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

namespace ltm::registration {
namespace {

using Eigen::Vector3f;

// Points on the plane through `c` with unit normal `n`, spread over +-half, Gaussian noise.
std::vector<Vector3f> plane_points(const Vector3f& c, const Vector3f& n, float half, int count,
                                   float noise, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-half, half);
    std::normal_distribution<float> e(0.0f, noise);
    const Vector3f a = n.unitOrthogonal(), b = n.cross(a);
    std::vector<Vector3f> pts;
    for (int i = 0; i < count; ++i) pts.push_back(c + u(rng) * a + u(rng) * b + e(rng) * n);
    return pts;
}

// Sums, centre and normal checked against a direct (two-pass, double) computation.
void expect_matches_brute_force(const std::vector<Vector3f>& pts, const Vector3f& cell,
                                const VoxelRecord& r, const Surfel& s) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : pts) mean += p.cast<double>();
    mean /= double(pts.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : pts) {
        const Eigen::Vector3d d = p.cast<double>() - mean;
        cov += d * d.transpose();
    }
    cov /= double(pts.size());
    EXPECT_NEAR(r.sums.weight, float(pts.size()), 1e-3);
    EXPECT_LT((s.centre.cast<double>() - mean).norm(), 1e-5);
    EXPECT_LT((r.sums.covariance() - cov).norm(), 1e-5);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    EXPECT_GT(std::abs(s.normal.cast<double>().dot(eig.eigenvectors().col(0))), 0.9999);
    (void)cell;
}

TEST(Voxel, PlaneGivesCentreNormalAndHighPlanarity) {
    const Vector3f cell(0.5f, 0.5f, 0.5f);
    const Vector3f n = Vector3f(0.2f, -0.3f, 1.0f).normalized();
    const auto pts = plane_points(cell + Vector3f(0.05f, -0.02f, 0.01f), n, 0.4f, 200, 0.005f, 1);
    VoxelConfig config;
    config.max_points = 1000;
    VoxelRecord r;
    Surfel s;
    for (const auto& p : pts) r.sums.add(p - cell);
    update_surfel(config, 1.0f, cell, Vector3f(0, 0, 10), r, s);
    expect_matches_brute_force(pts, cell, r, s);
    EXPECT_GT(std::abs(s.normal.dot(n)), 0.999f);
    EXPECT_GT(s.normal.dot(Vector3f(0, 0, 10) - s.centre), 0.0f);  // oriented to the sensor
    EXPECT_GT(s.planarity, 0.95f);
    EXPECT_EQ(s.usable, 1u);
    EXPECT_FLOAT_EQ(s.stability, float(config.initial_stability));
    EXPECT_EQ(r.previous_normal.squaredNorm(), 0.0f);
}

TEST(Voxel, EdgeGivesBisectorNormalAndLowerPlanarity) {
    // Two perpendicular faces meeting along the y axis of the cell: x = 0 (z > 0) and z = 0 (x >
    // 0).
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(0.0f, 0.5f), w(-0.5f, 0.5f);
    std::vector<Vector3f> pts;
    for (int i = 0; i < 300; ++i) {
        pts.emplace_back(0.0f, w(rng), u(rng));
        pts.emplace_back(u(rng), w(rng), 0.0f);
    }
    VoxelConfig config;
    config.max_points = 1000;
    VoxelRecord r;
    Surfel s;
    for (const auto& p : pts) r.sums.add(p);
    update_surfel(config, 1.0f, Vector3f::Zero(), Vector3f(5, 0, 5), r, s);
    expect_matches_brute_force(pts, Vector3f::Zero(), r, s);
    const Vector3f bisector = Vector3f(1, 0, 1).normalized();
    EXPECT_GT(s.normal.dot(bisector), 0.99f);
    // Analytically l_min / l_mid = (L^2/24) / (L^2/6) for two equal faces: planarity 0.75.
    EXPECT_NEAR(s.planarity, 0.75f, 0.05f);
}

TEST(Voxel, LineIsNotUsable) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    std::normal_distribution<float> e(0.0f, 0.005f);
    VoxelConfig config;
    VoxelRecord r;
    Surfel s;
    for (int i = 0; i < 50; ++i) r.sums.add(Vector3f(u(rng), e(rng), e(rng)));
    update_surfel(config, 1.0f, Vector3f::Zero(), Vector3f(0, 0, 10), r, s);
    EXPECT_LT(s.planarity, float(config.min_planarity));
    EXPECT_EQ(s.usable, 0u);
}

TEST(Voxel, TooFewPointsHaveNoNormal) {
    VoxelConfig config;
    VoxelRecord r;
    Surfel s;
    for (int i = 0; i < config.min_points_for_normal - 1; ++i)
        r.sums.add(Vector3f(0.1f * i, 0.05f * i * i, 0));
    update_surfel(config, 1.0f, Vector3f::Zero(), Vector3f(0, 0, 10), r, s);
    EXPECT_EQ(s.usable, 0u);
    EXPECT_EQ(s.normal.squaredNorm(), 0.0f);
}

TEST(Voxel, StabilityIsCosineBetweenOldAndNewNormal) {
    VoxelConfig config;
    config.max_points = 1e6;
    VoxelRecord r;
    Surfel s;
    const Vector3f n0(0, 0, 1);
    for (const auto& p : plane_points(Vector3f::Zero(), n0, 0.4f, 100, 0.0f, 4)) r.sums.add(p);
    update_surfel(config, 1.0f, Vector3f::Zero(), Vector3f(0, 0, 10), r, s);
    const Vector3f old_normal = s.normal;
    // A tilted plane through the same centre, with many more points: the normal turns.
    const Vector3f n1 = Vector3f(0, std::sin(0.5f), std::cos(0.5f));
    for (const auto& p : plane_points(Vector3f::Zero(), n1, 0.4f, 2000, 0.0f, 5)) r.sums.add(p);
    update_surfel(config, 1.0f, Vector3f::Zero(), Vector3f(0, 0, 10), r, s);
    EXPECT_EQ(r.previous_normal, old_normal);
    EXPECT_NEAR(s.stability, std::abs(s.normal.dot(old_normal)), 1e-6f);
    EXPECT_LT(s.stability, 0.97f);
    EXPECT_GT(s.normal.dot(old_normal), 0.0f);  // kept the orientation of the old normal
}

TEST(Voxel, WeightIsCappedWithoutMovingTheCentre) {
    VoxelConfig config;
    config.max_points = 40;
    VoxelRecord r;
    Surfel s;
    const auto pts = plane_points(Vector3f(0.1f, 0, 0), Vector3f::UnitZ(), 0.4f, 100, 0.01f, 6);
    for (const auto& p : pts) r.sums.add(p);
    const Vector3f mean = r.sums.mean();
    update_surfel(config, 1.0f, Vector3f::Zero(), Vector3f(0, 0, 10), r, s);
    EXPECT_NEAR(r.sums.weight, 40.0f, 1e-4f);
    EXPECT_LT((s.centre - mean).norm(), 1e-5f);
}

}  // namespace
}  // namespace ltm::registration
