#include "simulator/core/bvh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "simulator/core/random.hpp"

namespace ltm::sim {
namespace {

Eigen::Vector3f random_unit(Rng& rng) {
    const double z = rng.uniform(-1, 1), a = rng.uniform(0, 2 * M_PI);
    const double r = std::sqrt(1 - z * z);
    return Eigen::Vector3f(float(r * std::cos(a)), float(r * std::sin(a)), float(z));
}

TEST(Bvh, HitsPlaneAtAnalyticDistance) {
    Mesh mesh;
    MeshBuilder b(mesh);
    b.quad({-500, -500, 0}, {500, -500, 0}, {500, 500, 0}, {-500, 500, 0});
    const Bvh bvh(mesh);
    Rng rng(1);
    for (int k = 0; k < 500; ++k) {
        const Eigen::Vector3f o(float(rng.uniform(-50, 50)), float(rng.uniform(-50, 50)),
                                float(rng.uniform(0.5, 5)));
        Eigen::Vector3f d = random_unit(rng);
        d.z() = -std::abs(d.z()) - 0.05f;
        d.normalize();
        RayHit hit;
        ASSERT_TRUE(bvh.intersect(o, d, 0.0f, 1e4f, hit));
        EXPECT_NEAR(hit.t, -o.z() / d.z(), 1e-3 * (1 + hit.t));
        Eigen::Vector3f up(0, 0, 1);
        EXPECT_NEAR(std::abs(bvh.normal(hit.triangle).dot(up)), 1.0, 1e-6);
        EXPECT_FALSE(bvh.intersect(o, -d, 0.0f, 1e4f, hit));  // away from the plane
    }
}

TEST(Bvh, HitsBoxAtSlabDistance) {
    Mesh mesh;
    MeshBuilder b(mesh);
    const Eigen::Vector3d lo(-1, -2, 0), hi(3, 1, 2.5);
    b.box(lo, hi);
    const Bvh bvh(mesh);
    Rng rng(2);
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
        const Eigen::Vector3f o = random_unit(rng) * 10.0f;
        const Eigen::Vector3f target(float(rng.uniform(-3, 5)), float(rng.uniform(-4, 3)),
                                     float(rng.uniform(-1, 4)));
        const Eigen::Vector3f d = (target - o).normalized();  // about half of them hit
        // Analytic slab test.
        double t0 = 0, t1 = 1e9;
        for (int a = 0; a < 3; ++a) {
            double p = (lo[a] - o[a]) / d[a], q = (hi[a] - o[a]) / d[a];
            if (p > q) std::swap(p, q);
            t0 = std::max(t0, p);
            t1 = std::min(t1, q);
        }
        const bool expect = t0 <= t1;
        RayHit hit;
        const bool got = bvh.intersect(o, d, 0.0f, 1e4f, hit);
        if (expect && t1 - t0 > 1e-3) {
            ASSERT_TRUE(got);
            EXPECT_NEAR(hit.t, t0, 1e-4);
            ++hits;
        } else if (!expect && t0 - t1 > 1e-3) {
            EXPECT_FALSE(got);
        }
    }
    EXPECT_GT(hits, 500);
}

TEST(Bvh, HitsCylinderWithinFacetError) {
    const double r = 0.8;
    const int segments = 48;
    Mesh mesh;
    MeshBuilder b(mesh);
    b.cylinder({0, 0, 0}, {0, 0, 3}, r, segments);
    const Bvh bvh(mesh);
    Rng rng(3);
    // Horizontal rays aimed at the axis: the facets lie between r cos(pi/N) and r from it.
    const double facet = r * (1 - std::cos(M_PI / segments));
    for (int k = 0; k < 500; ++k) {
        const double a = rng.uniform(0, 2 * M_PI), dist = rng.uniform(2, 30),
                     z = rng.uniform(0.1, 2.9);
        const Eigen::Vector3f o(float(dist * std::cos(a)), float(dist * std::sin(a)), float(z));
        const Eigen::Vector3f d = Eigen::Vector3f(-o.x(), -o.y(), 0).normalized();
        RayHit hit;
        ASSERT_TRUE(bvh.intersect(o, d, 0.0f, 100.0f, hit));
        EXPECT_GE(hit.t, dist - r - 1e-4);
        EXPECT_LE(hit.t, dist - r + facet + 1e-4);
    }
    // Rays passing beside it miss.
    RayHit hit;
    EXPECT_FALSE(bvh.intersect({5, r + 0.05f, 1}, {-1, 0, 0}, 0.0f, 100.0f, hit));
}

TEST(Bvh, MatchesBruteForceOnRandomTriangles) {
    Rng rng(4);
    Mesh mesh;
    MeshBuilder b(mesh);
    for (int k = 0; k < 3000; ++k) {
        const Eigen::Vector3d c(rng.uniform(-40, 40), rng.uniform(-40, 40), rng.uniform(-5, 15));
        auto jitter = [&] {
            return Eigen::Vector3d(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
        };
        b.triangle(c + jitter(), c + jitter(), c + jitter());
    }
    const Bvh bvh(mesh);
    for (int k = 0; k < 2000; ++k) {
        const Eigen::Vector3f o(float(rng.uniform(-50, 50)), float(rng.uniform(-50, 50)),
                                float(rng.uniform(-10, 20)));
        const Eigen::Vector3f d = random_unit(rng);
        float best = std::numeric_limits<float>::max();
        int best_id = -1;
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {  // Moller-Trumbore, double
            const Eigen::Vector3d v0 = mesh.vertices[mesh.triangles[t][0]].cast<double>();
            const Eigen::Vector3d e1 = mesh.vertices[mesh.triangles[t][1]].cast<double>() - v0;
            const Eigen::Vector3d e2 = mesh.vertices[mesh.triangles[t][2]].cast<double>() - v0;
            const Eigen::Vector3d dd = d.cast<double>(), s = o.cast<double>() - v0;
            const Eigen::Vector3d p = dd.cross(e2);
            const double det = e1.dot(p);
            if (std::abs(det) < 1e-12) continue;
            const double u = s.dot(p) / det;
            const Eigen::Vector3d q = s.cross(e1);
            const double v = dd.dot(q) / det, tt = e2.dot(q) / det;
            if (u >= 0 && v >= 0 && u + v <= 1 && tt > 0 && tt < best) {
                best = float(tt);
                best_id = static_cast<int>(t);
            }
        }
        RayHit hit;
        const bool got = bvh.intersect(o, d, 0.0f, std::numeric_limits<float>::max(), hit);
        ASSERT_EQ(got, best_id >= 0) << "ray " << k;
        if (got) {
            EXPECT_NEAR(hit.t, best, 1e-3);
        }
    }
}

TEST(Bvh, RespectsRangeLimits) {
    Mesh mesh;
    MeshBuilder b(mesh);
    b.box({5, -1, -1}, {6, 1, 1});
    b.box({10, -1, -1}, {11, 1, 1});
    const Bvh bvh(mesh);
    RayHit hit;
    ASSERT_TRUE(bvh.intersect({0, 0, 0}, {1, 0, 0}, 0.0f, 100.0f, hit));
    EXPECT_NEAR(hit.t, 5.0, 1e-5);
    ASSERT_TRUE(bvh.intersect({0, 0, 0}, {1, 0, 0}, 6.5f, 100.0f, hit));  // starts past the first
    EXPECT_NEAR(hit.t, 10.0, 1e-5);
    EXPECT_FALSE(bvh.intersect({0, 0, 0}, {1, 0, 0}, 0.0f, 4.0f, hit));
    EXPECT_TRUE(Bvh(Mesh()).empty());
}

}  // namespace
}  // namespace ltm::sim
