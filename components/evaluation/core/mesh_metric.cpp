#include "evaluation/core/mesh_metric.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

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

// Whether a point lies within `radius` of any of `points` (a hash of radius-sized cells).
class Proximity {
  public:
    Proximity(const std::vector<Eigen::Vector3d>& points, double radius)
        : points_(points), radius_(radius) {
        for (std::size_t i = 0; i < points.size(); ++i) cells_[key(cell(points[i]))].push_back(i);
    }
    bool near(const Eigen::Vector3d& p) const {
        const Eigen::Vector3i c = cell(p);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
                    if (it == cells_.end()) continue;
                    for (const std::size_t i : it->second)
                        if ((points_[i] - p).squaredNorm() <= radius_ * radius_) return true;
                }
        return false;
    }

  private:
    Eigen::Vector3i cell(const Eigen::Vector3d& p) const {
        return (p / radius_).array().floor().cast<int>();
    }
    static std::uint64_t key(const Eigen::Vector3i& c) {
        return (std::uint64_t(std::uint32_t(c.x()) & 0x1FFFFFu) << 42) |
               (std::uint64_t(std::uint32_t(c.y()) & 0x1FFFFFu) << 21) |
               (std::uint64_t(std::uint32_t(c.z()) & 0x1FFFFFu));
    }
    const std::vector<Eigen::Vector3d>& points_;
    double radius_;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

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

double mesh_area(const common::PlyMesh& mesh) {
    const std::vector<Eigen::Vector3d> v = vertices_of(mesh);
    double total = 0.0;
    for (const auto& t : mesh.triangles)
        if (valid_triangle(t, v.size()))
            total += 0.5 * (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).norm();
    return total;
}

MeshMetricResult evaluate_mesh(const common::PlyMesh& mesh, const common::PlyMesh& truth,
                               const MeshMetricConfig& config,
                               const std::vector<Eigen::Vector3d>& crop_to) {
    MeshMetricResult r;
    r.threshold = config.threshold;
    const std::vector<Eigen::Vector3d> mesh_samples =
        sample_surface(mesh, config.samples, config.seed);
    std::vector<Eigen::Vector3d> truth_samples =
        sample_surface(truth, config.samples, config.seed + 1);
    if (!crop_to.empty()) {
        const Proximity observed(crop_to, config.crop_radius);
        const std::size_t before = truth_samples.size();
        truth_samples.erase(
            std::remove_if(truth_samples.begin(), truth_samples.end(),
                           [&](const Eigen::Vector3d& p) { return !observed.near(p); }),
            truth_samples.end());
        r.truth_cropped = before - truth_samples.size();
    }
    r.mesh_samples = mesh_samples.size();
    r.truth_samples = truth_samples.size();
    r.mesh_area = mesh_area(mesh);
    const std::size_t drawn = truth_samples.size() + r.truth_cropped;
    r.truth_area_scored =
        drawn ? mesh_area(truth) * double(truth_samples.size()) / double(drawn) : 0.0;
    if (mesh_samples.empty() || truth_samples.empty()) return r;

    const TriangleBvh mesh_bvh(vertices_of(mesh), mesh.triangles);
    const TriangleBvh truth_bvh(vertices_of(truth), truth.triangles);
    const std::vector<double> acc = distances(mesh_samples, truth_bvh);
    const std::vector<double> comp = distances(truth_samples, mesh_bvh);

    for (std::size_t i = 0; i < comp.size(); ++i)
        if (comp[i] > config.threshold) r.missed.push_back(truth_samples[i]);
    for (std::size_t i = 0; i < acc.size(); ++i)
        if (acc[i] > config.threshold) r.wrong.push_back(mesh_samples[i]);
    const ErrorStats a = summarize(acc), c = summarize(comp);
    r.accuracy_mean = a.mean;
    r.accuracy_median = percentile(acc, 50.0);
    r.accuracy_p90 = percentile(acc, 90.0);
    r.completeness_mean = c.mean;
    r.completeness_median = percentile(comp, 50.0);
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
