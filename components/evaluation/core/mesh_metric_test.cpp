#include "evaluation/core/mesh_metric.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

// A rectangle [0, w] x [0, 1] at height z, as two triangles.
common::PlyMesh rectangle(float w, float z) {
    common::PlyMesh m;
    m.vertices = {{0, 0, z}, {w, 0, z}, {w, 1, z}, {0, 1, z}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

TEST(MeshMetric, ParallelOffsetIsTheOffsetEverywhere) {
    MeshMetricConfig c;
    c.samples = 20000;
    const MeshMetricResult r = evaluate_mesh(rectangle(1, 0.1f), rectangle(1, 0), c);
    ASSERT_TRUE(r.valid);
    EXPECT_NEAR(r.accuracy_mean, 0.1, 1e-6);
    EXPECT_NEAR(r.accuracy_p90, 0.1, 1e-6);
    EXPECT_NEAR(r.completeness_mean, 0.1, 1e-6);
    EXPECT_NEAR(r.chamfer_l1, 0.1, 1e-6);
    EXPECT_DOUBLE_EQ(r.fscore_pct, 0.0);  // 0.1 m (as float: a hair over) > threshold 0.1 m
    c.threshold = 0.15;
    EXPECT_DOUBLE_EQ(evaluate_mesh(rectangle(1, 0.1f), rectangle(1, 0), c).fscore_pct, 100.0);
}

TEST(MeshMetric, HalfCoverageByHand) {
    // The mesh covers the left half of the true 2 x 1 rectangle. Accuracy 0. Completeness: half
    // the truth samples at 0, the other half at x - 1, uniform on [0, 1]: mean 0.25, 90th
    // percentile v with 0.5 + 0.5 v = 0.9 -> 0.8. Chamfer-L1 0.125. Recall at 0.1 m: 55 %.
    MeshMetricConfig c;
    c.samples = 100000;
    const MeshMetricResult r = evaluate_mesh(rectangle(1, 0), rectangle(2, 0), c);
    EXPECT_NEAR(r.accuracy_mean, 0.0, 1e-6);
    EXPECT_NEAR(r.completeness_mean, 0.25, 0.005);
    EXPECT_NEAR(r.completeness_p90, 0.8, 0.01);
    EXPECT_NEAR(r.chamfer_l1, 0.125, 0.003);
    EXPECT_DOUBLE_EQ(r.precision_pct, 100.0);
    EXPECT_NEAR(r.recall_pct, 55.0, 0.5);
}

TEST(MeshMetric, CropToWhatWasObservedAndMedians) {
    // Same half coverage, but only the covered half was observed (points on x in [0, 0.9]): the
    // unseen truth is not scored, completeness is 0. Without the crop the median is 0.0 (half
    // the samples at 0) and the mean 0.25.
    MeshMetricConfig c;
    c.samples = 20000;
    c.crop_radius = 0.05;
    std::vector<Eigen::Vector3d> observed;
    for (int i = 0; i <= 18; ++i)
        for (int j = 0; j <= 20; ++j) observed.emplace_back(0.05 * i, 0.05 * j, 0.0);
    const MeshMetricResult r = evaluate_mesh(rectangle(1, 0), rectangle(2, 0), c, observed);
    ASSERT_TRUE(r.valid);
    EXPECT_NEAR(double(r.truth_cropped) / double(c.samples), 0.525, 0.015);  // x > 0.95
    EXPECT_NEAR(r.completeness_mean, 0.0, 1e-6);
    EXPECT_NEAR(r.recall_pct, 100.0, 1e-9);
    const MeshMetricResult all = evaluate_mesh(rectangle(1, 0), rectangle(2, 0), c);
    EXPECT_EQ(all.truth_cropped, 0u);
    EXPECT_NEAR(all.completeness_mean, 0.25, 0.01);
    EXPECT_LT(all.completeness_median, 0.02);  // the median sample is at the covered edge
    EXPECT_NEAR(all.accuracy_median, 0.0, 1e-6);
    // The missed samples are the truth beyond x = 1.1 (0.1 m threshold); nothing is wrong.
    EXPECT_NEAR(double(all.missed.size()) / double(c.samples), 0.45, 0.015);
    for (const Eigen::Vector3d& p : all.missed) ASSERT_GT(p.x(), 1.1 - 1e-9);
    EXPECT_TRUE(all.wrong.empty());
    EXPECT_TRUE(r.missed.empty());
    EXPECT_NEAR(all.mesh_area, 1.0, 1e-9);
    EXPECT_NEAR(all.truth_area_scored, 2.0, 1e-9);
    EXPECT_NEAR(r.truth_area_scored, 2.0 * 0.475, 0.03);
}

TEST(MeshMetric, SamplesAreUniformByArea) {
    // Two triangles of areas 1 and 3 (disjoint): a quarter of the samples on the first.
    common::PlyMesh m;
    m.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {10, 0, 0}, {16, 0, 0}, {10, 1, 0}};
    m.triangles = {{0, 1, 2}, {3, 4, 5}};
    const auto s = sample_surface(m, 40000, 5);
    const auto first =
        std::count_if(s.begin(), s.end(), [](const Eigen::Vector3d& p) { return p.x() < 5; });
    EXPECT_NEAR(static_cast<double>(first) / s.size(), 0.25, 0.01);
}

TEST(MeshMetric, PointCloudsAndEmptySurfaces) {
    common::PlyMesh cloud;
    cloud.vertices = {{0.5f, 0.5f, 0.2f}};
    MeshMetricConfig c;
    c.samples = 1000;
    const MeshMetricResult r = evaluate_mesh(cloud, rectangle(1, 0), c);
    EXPECT_EQ(r.mesh_samples, 1u);
    EXPECT_NEAR(r.accuracy_mean, 0.2, 1e-6);
    EXPECT_FALSE(evaluate_mesh(common::PlyMesh{}, rectangle(1, 0), c).valid);
}

}  // namespace
}  // namespace ltm::eval
