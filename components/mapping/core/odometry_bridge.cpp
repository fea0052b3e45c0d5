#include "mapping/core/odometry_bridge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ltm::mapping {
namespace {

constexpr int kDiscPoints = 8;

// The rebuilt voxels' usability was decided from the data: the grid must not undo it.
odometry::VoxelConfig rebuild_voxel_config() {
    odometry::VoxelConfig c;
    c.min_points_for_normal = kDiscPoints;
    c.min_planarity = 0.3;
    c.min_extent = 0.0;
    c.max_points = 1e9;
    return c;
}

// How far c can move along d (unit) and -d before leaving the box [lo, hi].
float room(const Eigen::Vector3f& c, const Eigen::Vector3f& d, const Eigen::Vector3f& lo,
           const Eigen::Vector3f& hi) {
    float t = std::numeric_limits<float>::infinity();
    for (int i = 0; i < 3; ++i) {
        const float a = std::abs(d[i]);
        if (a < 1e-6f) continue;
        t = std::min(t, std::min(hi[i] - c[i], c[i] - lo[i]) / a);
    }
    return t;
}

}  // namespace

RegistrationTarget rebuild_registration_target(const common::LocalMapData& data,
                                               double min_planarity, int coarse_factor) {
    const double g = data.voxel_size > 0.0f ? double(data.voxel_size) : 1.0;
    const odometry::VoxelConfig vc = rebuild_voxel_config();
    RegistrationTarget t{odometry::VoxelGrid(g, vc), std::nullopt, data.T_anchor_grid, 0};
    const float gf = float(g);
    std::vector<Eigen::Vector3f> points, centres;
    points.reserve(data.voxels.size() * kDiscPoints);
    for (const common::VoxelData& v : data.voxels) {
        const Eigen::Vector3f lo = v.index.cast<float>() * gf;
        const Eigen::Vector3f hi = lo.array() + gf;
        const float tol = 1e-3f * gf;
        if (!v.centre.allFinite() || ((v.centre - lo).array() < -tol).any() ||
            ((hi - v.centre).array() < -tol).any()) {
            ++t.skipped_voxels;  // a centre outside its own cell: not a voxel of this lattice
            continue;
        }
        const float inset = 0.01f * gf;  // a centre on a cell face moves just inside
        const Eigen::Vector3f c =
            v.centre.array().max(lo.array() + inset).min(hi.array() - inset).matrix();
        const Eigen::Vector3f& n = v.normal;
        const bool usable = n.allFinite() && std::abs(n.norm() - 1.0f) < 1e-2f &&
                            double(v.planarity) >= min_planarity;
        if (!usable) {
            centres.push_back(c);  // present, without a normal (one point)
            continue;
        }
        const Eigen::Vector3f nn = n.normalized();
        const Eigen::Vector3f u = nn.unitOrthogonal();
        const Eigen::Vector3f w = nn.cross(u);
        Eigen::Vector3f dirs[kDiscPoints];
        float r = 0.25f * gf;
        for (int k = 0; k < kDiscPoints; ++k) {
            const float a = float(2.0 * M_PI * k / kDiscPoints);
            dirs[k] = std::cos(a) * u + std::sin(a) * w;
            r = std::min(r, 0.95f * room(c, dirs[k], lo, hi));
        }
        r = std::max(r, 0.002f * gf);
        for (int k = 0; k < kDiscPoints; ++k) points.push_back(c + r * dirs[k]);
    }
    // IMLS aligns the normals' signs itself: one pass, any sensor position.
    auto all = [](const Eigen::Vector3f&) { return true; };
    const Eigen::Vector3f sensor = data.T_anchor_grid.inverse().translation().cast<float>();
    t.fine.integrate(points, sensor, 0.0, all);
    t.fine.integrate(centres, sensor, 0.0, all);
    if (coarse_factor >= 2) {
        odometry::VoxelConfig cc;  // the odometry's defaults: planes fitted to the discs
        t.coarse.emplace(g * coarse_factor, cc);
        t.coarse->integrate(points, sensor, 0.0, all);
    }
    return t;
}

}  // namespace ltm::mapping
