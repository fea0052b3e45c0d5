#include "mesh/core/test_surfaces.hpp"

#include <cmath>

namespace ltm::mesh::test {

namespace {

common::VoxelData voxel(const Eigen::Vector3i& index, const Eigen::Vector3d& centre,
                        const Eigen::Vector3d& normal) {
    common::VoxelData v;
    v.index = index;
    v.centre = centre.cast<float>();
    v.normal = normal.normalized().cast<float>();
    v.point_count = 20;
    v.planarity = 1.0f;
    v.stability = 1.0f;
    v.life.observations = 10;
    v.life.health = 1.0f;
    return v;
}

bool inside_cell(const Eigen::Vector3d& p, const Eigen::Vector3i& index, double s) {
    const Eigen::Vector3d lo = index.cast<double>() * s;
    return (p.array() >= lo.array()).all() && (p.array() < (lo.array() + s)).all();
}

}  // namespace

std::vector<common::VoxelData> plane_voxels(const Eigen::Vector3d& n_in, double offset,
                                            const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                            double s) {
    const Eigen::Vector3d n = n_in.normalized();
    std::vector<common::VoxelData> out;
    const Eigen::Vector3i a((lo / s).array().floor().cast<int>());
    const Eigen::Vector3i b((hi / s).array().floor().cast<int>());
    for (int z = a.z(); z <= b.z(); ++z)
        for (int y = a.y(); y <= b.y(); ++y)
            for (int x = a.x(); x <= b.x(); ++x) {
                const Eigen::Vector3i idx(x, y, z);
                const Eigen::Vector3d c = (idx.cast<double>() + Eigen::Vector3d::Constant(0.5)) * s;
                const Eigen::Vector3d p = c - (n.dot(c) - offset) * n;
                if (!inside_cell(p, idx, s)) continue;
                if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
                out.push_back(voxel(idx, p, n));
            }
    return out;
}

std::vector<common::VoxelData> sphere_voxels(const Eigen::Vector3d& centre, double radius,
                                             double s) {
    std::vector<common::VoxelData> out;
    const Eigen::Vector3i a(((centre.array() - radius - s) / s).floor().cast<int>());
    const Eigen::Vector3i b(((centre.array() + radius + s) / s).floor().cast<int>());
    for (int z = a.z(); z <= b.z(); ++z)
        for (int y = a.y(); y <= b.y(); ++y)
            for (int x = a.x(); x <= b.x(); ++x) {
                const Eigen::Vector3i idx(x, y, z);
                const Eigen::Vector3d c = (idx.cast<double>() + Eigen::Vector3d::Constant(0.5)) * s;
                const Eigen::Vector3d r = c - centre;
                if (r.norm() < 1e-9) continue;
                const Eigen::Vector3d p = centre + radius * r.normalized();
                if (!inside_cell(p, idx, s)) continue;
                out.push_back(voxel(idx, p, r));
            }
    return out;
}

common::LocalMapData local_map(std::uint64_t id, const std::vector<common::VoxelData>& voxels,
                               double voxel_size, const Eigen::Isometry3d& T_odom_anchor,
                               const Eigen::Isometry3d& T_anchor_grid) {
    common::LocalMapData m;
    m.id = id;
    m.revision = 1;
    m.finished = true;
    m.T_odom_anchor = T_odom_anchor;
    m.T_anchor_grid = T_anchor_grid;
    m.voxel_size = float(voxel_size);
    m.voxels = voxels;
    return m;
}

int crossings(const common::PlyMesh& mesh, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    // Moller-Trumbore on the segment.
    int hits = 0;
    const Eigen::Vector3d dir = b - a;
    for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d v0 = mesh.vertices[t[0]].cast<double>();
        const Eigen::Vector3d e1 = mesh.vertices[t[1]].cast<double>() - v0;
        const Eigen::Vector3d e2 = mesh.vertices[t[2]].cast<double>() - v0;
        const Eigen::Vector3d p = dir.cross(e2);
        const double det = e1.dot(p);
        if (std::abs(det) < 1e-12) continue;
        const Eigen::Vector3d s = a - v0;
        const double u = s.dot(p) / det;
        if (u < 0.0 || u > 1.0) continue;
        const Eigen::Vector3d q = s.cross(e1);
        const double v = dir.dot(q) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        const double tt = e2.dot(q) / det;
        if (tt >= 0.0 && tt <= 1.0) ++hits;
    }
    return hits;
}

}  // namespace ltm::mesh::test
