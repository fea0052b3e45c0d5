#include "evaluation/core/mesh_metric.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "evaluation/core/stats.hpp"
#include "evaluation/core/triangle_bvh.hpp"

namespace ltm::eval {
namespace {

bool valid_triangle(const Eigen::Vector3i& t, std::size_t nv) {
    return t.minCoeff() >= 0 && static_cast<std::size_t>(t.maxCoeff()) < nv;
}

std::vector<Eigen::Vector3d> vertices_of(const common::PlyMesh& mesh) {
    std::vector<Eigen::Vector3d> v;
    v.reserve(mesh.vertices.size());
    for (const auto& p : mesh.vertices) v.push_back(p.cast<double>());
    return v;
}

// Distances from every sample to the surface.
std::vector<double> distances(const std::vector<Eigen::Vector3d>& samples, const TriangleBvh& to) {
    std::vector<double> d;
    d.reserve(samples.size());
    for (const auto& s : samples) d.push_back(to.distance(s));
    return d;
}

double share_within(const std::vector<double>& d, double threshold) {
    if (d.empty()) return 0.0;
    const auto n = std::count_if(d.begin(), d.end(), [&](double x) { return x <= threshold; });
    return 100.0 * static_cast<double>(n) / static_cast<double>(d.size());
}

}  // namespace

std::vector<Eigen::Vector3d> sample_surface(const common::PlyMesh& mesh, std::size_t count,
                                            std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const std::vector<Eigen::Vector3d> v = vertices_of(mesh);
    std::vector<Eigen::Vector3d> out;

    std::vector<const Eigen::Vector3i*> tris;
    std::vector<double> cumulative;
    double total = 0.0;
    for (const auto& t : mesh.triangles) {
        if (!valid_triangle(t, v.size())) continue;
        total += 0.5 * (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).norm();
        tris.push_back(&t);
        cumulative.push_back(total);
    }
    if (tris.empty() || total <= 0.0) {
        // A point cloud (or only degenerate triangles): its points, or a random subset.
        out = v;
        if (out.size() > count) {
            std::shuffle(out.begin(), out.end(), rng);
            out.resize(count);
        }
        return out;
    }
    out.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
        const double r = u(rng) * total;
        const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), r);
        const std::size_t i = std::min<std::size_t>(it - cumulative.begin(), tris.size() - 1);
        const Eigen::Vector3i& t = *tris[i];
        // Uniform on the triangle: a = 1 - sqrt(r1), b = sqrt(r1) (1 - r2), c = sqrt(r1) r2.
        const double s = std::sqrt(u(rng)), r2 = u(rng);
        out.push_back((1.0 - s) * v[t[0]] + s * (1.0 - r2) * v[t[1]] + s * r2 * v[t[2]]);
    }
    return out;
}

MeshMetricResult evaluate_mesh(const common::PlyMesh& mesh, const common::PlyMesh& truth,
                               const MeshMetricConfig& config) {
    MeshMetricResult r;
    r.threshold = config.threshold;
    const std::vector<Eigen::Vector3d> mesh_samples =
        sample_surface(mesh, config.samples, config.seed);
    const std::vector<Eigen::Vector3d> truth_samples =
        sample_surface(truth, config.samples, config.seed + 1);
    r.mesh_samples = mesh_samples.size();
    r.truth_samples = truth_samples.size();
    if (mesh_samples.empty() || truth_samples.empty()) return r;

    const TriangleBvh mesh_bvh(vertices_of(mesh), mesh.triangles);
    const TriangleBvh truth_bvh(vertices_of(truth), truth.triangles);
    const std::vector<double> acc = distances(mesh_samples, truth_bvh);
    const std::vector<double> comp = distances(truth_samples, mesh_bvh);

    const ErrorStats a = summarize(acc), c = summarize(comp);
    r.accuracy_mean = a.mean;
    r.accuracy_p90 = percentile(acc, 90.0);
    r.completeness_mean = c.mean;
    r.completeness_p90 = percentile(comp, 90.0);
    r.chamfer_l1 = 0.5 * (a.mean + c.mean);
    r.precision_pct = share_within(acc, config.threshold);
    r.recall_pct = share_within(comp, config.threshold);
    if (r.precision_pct + r.recall_pct > 0.0)
        r.fscore_pct = 2.0 * r.precision_pct * r.recall_pct / (r.precision_pct + r.recall_pct);
    r.valid = true;
    return r;
}

}  // namespace ltm::eval
