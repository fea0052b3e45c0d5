#include "mesh/core/sdf_mesher.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include "mesh/core/triangle_mesh.hpp"

namespace ltm::mesh {

namespace {

using Clock = std::chrono::steady_clock;
// (sum of weights, sum of weighted distances) per grid point: one tree walk for both.
using Vec2STree = openvdb::tree::Tree4<openvdb::Vec2s, 5, 4, 3>::Type;
using Vec2SGrid = openvdb::Grid<Vec2STree>;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

void initialise_openvdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

bool usable(const common::VoxelData& v, int min_points) {
    const float n2 = v.normal.squaredNorm();
    return v.centre.allFinite() && v.normal.allFinite() && n2 > 0.25f && n2 < 4.0f &&
           int(v.point_count) >= min_points;
}

}  // namespace

std::vector<SurfaceVoxel> surface_voxels(const std::vector<common::VoxelData>& voxels,
                                         const MeshConfig& config, std::size_t* left_out) {
    std::vector<SurfaceVoxel> out;
    out.reserve(voxels.size());
    std::size_t left = 0;
    for (const common::VoxelData& v : voxels) {
        double base = config.planarity_floor + std::clamp(double(v.planarity), 0.0, 1.0);
        if (config.use_health) base *= std::clamp(double(v.life.health), 0.0, 1.0);
        if (!usable(v, config.min_points) || !(base > 0.0)) {
            ++left;
            continue;
        }
        out.push_back({v.centre, v.normal.normalized(), float(base)});
    }
    if (left_out) *left_out = left;
    return out;
}

common::PlyMesh mesh_voxels(const std::vector<common::VoxelData>& voxels, double voxel_size,
                            const MeshConfig& config, SdfStats* stats) {
    std::size_t left = 0;
    const std::vector<SurfaceVoxel> surface = surface_voxels(voxels, config, &left);
    common::PlyMesh mesh = mesh_surface(surface, voxel_size, config, stats);
    if (stats) stats->voxels_left = left;
    return mesh;
}

common::PlyMesh mesh_surface(const std::vector<SurfaceVoxel>& voxels, double voxel_size,
                             const MeshConfig& config, SdfStats* stats) {
    common::throw_if(validate(config), "mesh");
    if (!(voxel_size > 0.0) || !std::isfinite(voxel_size))
        throw common::ConfigError("mesh.voxel_size", "must be > 0 (the local map's voxel size)");
    initialise_openvdb();
    SdfStats local;
    SdfStats& s = stats ? *stats : local;
    s = SdfStats{};

    const double g = effective_grid_size(config, voxel_size);
    const double tau = effective_truncation(config, voxel_size);
    const double support = config.support * voxel_size;
    const double support2 = support * support;
    const double h = config.kernel * voxel_size;
    const double inv_h2 = 1.0 / (h * h);
    const int reach = int(std::ceil(std::max(support, tau) / g));

    // Weighted sums per grid point (index space: q = ijk * g): (sum of w, sum of w * d).
    const auto t_fill = Clock::now();
    Vec2SGrid::Ptr sums = Vec2SGrid::create(openvdb::Vec2s(0.0f, 0.0f));
    {
        auto acc = sums->getAccessor();
        const float gf = float(g), tauf = float(tau), support2f = float(support2);
        const float inv_h2f = float(inv_h2);
        for (const SurfaceVoxel& v : voxels) {
            if (!(v.weight > 0.0f) || !v.centre.allFinite() || !v.normal.allFinite()) continue;
            const Eigen::Vector3f& c = v.centre;
            const Eigen::Vector3f& n = v.normal;
            const Eigen::Vector3i o((c / gf).array().round().cast<int>());
            ++s.voxels_used;
            for (int dz = -reach; dz <= reach; ++dz)
                for (int dy = -reach; dy <= reach; ++dy)
                    for (int dx = -reach; dx <= reach; ++dx) {
                        const openvdb::Coord ijk(o.x() + dx, o.y() + dy, o.z() + dz);
                        const Eigen::Vector3f dq =
                            Eigen::Vector3f(float(ijk.x()) * gf, float(ijk.y()) * gf,
                                            float(ijk.z()) * gf) -
                            c;
                        const float d = n.dot(dq);
                        if (std::abs(d) > tauf) continue;
                        const float r2 = dq.squaredNorm();
                        if (r2 - d * d > support2f) continue;
                        const float w = v.weight * std::exp(-r2 * inv_h2f);
                        acc.modifyValue(ijk, [w, d](openvdb::Vec2s& x) {
                            x[0] += w;
                            x[1] += w * d;
                        });
                    }
        }
    }
    // The signed distance where the weight suffices; elsewhere the background (+tau, inactive).
    openvdb::FloatGrid::Ptr sdf = openvdb::FloatGrid::create(float(tau));
    sdf->setTransform(openvdb::math::Transform::createLinearTransform(g));
    sdf->setGridClass(openvdb::GRID_LEVEL_SET);
    {
        auto acc = sdf->getAccessor();
        const float min_w = float(config.min_weight);
        for (auto it = sums->cbeginValueOn(); it; ++it) {
            const float w = (*it)[0];
            if (!(w > 0.0f) || w < min_w) continue;
            const float d = (*it)[1] / w;
            acc.setValueOn(it.getCoord(), std::clamp(d, -float(tau), float(tau)));
            ++s.grid_points;
        }
    }
    s.fill_ms = ms_since(t_fill);

    const auto t_mesh = Clock::now();
    common::PlyMesh mesh;
    if (s.grid_points == 0) {
        s.mesh_ms = ms_since(t_mesh);
        return mesh;
    }
    openvdb::tools::VolumeToMesh mesher(0.0, 0.0);
    mesher(*sdf);

    // A polygon is kept when every vertex lies in a cell whose 8 corners have a value: a surface
    // between a value and the background is the band's edge, not the surface.
    const auto acc = sdf->getConstAccessor();
    const double inv_g = 1.0 / g;
    const std::size_t n_points = mesher.pointListSize();
    std::vector<std::int8_t> cell_ok(n_points, -1);
    auto point_ok = [&](std::uint32_t i) {
        if (cell_ok[i] >= 0) return cell_ok[i] > 0;
        const openvdb::Vec3s& p = mesher.pointList()[i];
        const openvdb::Coord lo(int(std::floor(p.x() * inv_g)), int(std::floor(p.y() * inv_g)),
                                int(std::floor(p.z() * inv_g)));
        bool ok = true;
        for (int k = 0; k < 8 && ok; ++k)
            ok = acc.isValueOn(lo.offsetBy(k & 1, (k >> 1) & 1, (k >> 2) & 1));
        cell_ok[i] = ok ? 1 : 0;
        return ok;
    };
    std::vector<std::int64_t> remap(n_points, -1);
    auto vertex = [&](std::uint32_t i) {
        if (remap[i] < 0) {
            const openvdb::Vec3s& p = mesher.pointList()[i];
            remap[i] = std::int64_t(mesh.vertices.size());
            mesh.vertices.emplace_back(p.x(), p.y(), p.z());
        }
        return int(remap[i]);
    };
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        // VolumeToMesh winds faces towards negative values: reverse for the sensor's side.
        mesh.triangles.emplace_back(vertex(a), vertex(c), vertex(b));
    };
    for (std::size_t pi = 0; pi < mesher.polygonPoolListSize(); ++pi) {
        const openvdb::tools::PolygonPool& pool = mesher.polygonPoolList()[pi];
        for (std::size_t i = 0; i < pool.numQuads(); ++i) {
            const openvdb::Vec4I& q = pool.quad(i);
            if (!(point_ok(q[0]) && point_ok(q[1]) && point_ok(q[2]) && point_ok(q[3]))) {
                ++s.cells_dropped;
                continue;
            }
            add(q[0], q[1], q[2]);
            add(q[0], q[2], q[3]);
        }
        for (std::size_t i = 0; i < pool.numTriangles(); ++i) {
            const openvdb::Vec3I& t = pool.triangle(i);
            if (!(point_ok(t[0]) && point_ok(t[1]) && point_ok(t[2]))) {
                ++s.cells_dropped;
                continue;
            }
            add(t[0], t[1], t[2]);
        }
    }
    if (config.vertex_normals) mesh.normals = vertex_normals(mesh);
    s.mesh_ms = ms_since(t_mesh);
    return mesh;
}

}  // namespace ltm::mesh
