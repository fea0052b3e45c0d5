#include "mesh/core/mesh_chunk.hpp"

#include <cmath>

#include "mesh/core/triangle_mesh.hpp"

namespace ltm::mesh {

std::uint64_t cell_key(const Eigen::Vector3d& p, double cell_size) {
    const auto part = [&](double x) {
        return std::uint64_t(std::int64_t(std::floor(x / cell_size))) & 0x1FFFFFu;
    };
    return (part(p.x()) << 42) | (part(p.y()) << 21) | part(p.z());
}

bool MeshChunk::covers(const Eigen::Vector3d& p_grid) const {
    return cells.count(cell_key(p_grid, cell_size)) > 0;
}

MeshChunk make_chunk(const common::LocalMapData& map, const MeshConfig& config) {
    MeshChunk c;
    c.local_map_id = map.id;
    c.revision = map.revision;
    c.segment = map.segment;
    c.T_odom_anchor = map.T_odom_anchor;
    c.T_anchor_grid = map.T_anchor_grid;
    c.cell_size = config.ownership_cell * double(map.voxel_size);
    const common::PlyMesh grid_mesh = mesh_voxels(map.voxels, map.voxel_size, config, &c.stats);
    c.mesh = transformed(grid_mesh, map.T_anchor_grid);

    // Ownership cells and the bounding sphere (anchor frame) of the voxels and the mesh.
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    auto grow = [&](const Eigen::Vector3d& p) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    };
    for (const common::VoxelData& v : map.voxels) {
        if (!v.centre.allFinite() || v.normal.squaredNorm() < 0.25f ||
            int(v.point_count) < config.min_points)
            continue;
        const Eigen::Vector3d p = v.centre.cast<double>();
        c.cells.insert(cell_key(p, c.cell_size));
        grow(map.T_anchor_grid * p);
    }
    for (const Eigen::Vector3f& v : c.mesh.vertices) grow(v.cast<double>());
    if ((hi - lo).minCoeff() >= 0.0) {
        c.centre = 0.5 * (lo + hi);
        // The cells reach up to a cell diagonal beyond the voxel centres.
        c.radius = 0.5 * (hi - lo).norm() + c.cell_size * std::sqrt(3.0);
    }
    return c;
}

}  // namespace ltm::mesh
