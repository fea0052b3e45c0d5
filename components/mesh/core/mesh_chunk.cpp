#include "mesh/core/mesh_chunk.hpp"

#include <cmath>

#include "mesh/core/triangle_mesh.hpp"

namespace ltm::mesh {

namespace {

constexpr std::uint64_t kMask = 0x1FFFFFu;  // 21 bits a coordinate, two's complement

std::int32_t unpack(std::uint64_t bits) {
    return std::int32_t(bits & 0x100000u ? std::int64_t(bits) - std::int64_t(kMask + 1)
                                         : std::int64_t(bits));
}

}  // namespace

std::uint64_t cell_key(const Eigen::Vector3i& c) {
    return ((std::uint64_t(std::uint32_t(c.x())) & kMask) << 42) |
           ((std::uint64_t(std::uint32_t(c.y())) & kMask) << 21) |
           (std::uint64_t(std::uint32_t(c.z())) & kMask);
}

std::uint64_t cell_key(const Eigen::Vector3d& p, double cell_size) {
    return cell_key(Eigen::Vector3i((p / cell_size).array().floor().cast<int>()));
}

Eigen::Vector3i cell_index(std::uint64_t key) {
    return {unpack((key >> 42) & kMask), unpack((key >> 21) & kMask), unpack(key & kMask)};
}

Eigen::Vector3d cell_centre(std::uint64_t key, double cell_size) {
    return (cell_index(key).cast<double>() + Eigen::Vector3d::Constant(0.5)) * cell_size;
}

bool MeshChunk::covers(const Eigen::Vector3d& p_grid) const {
    return cells.count(cell_key(p_grid, cell_size)) > 0;
}

MeshChunk prepare_chunk(const common::LocalMapData& map, const MeshConfig& config) {
    common::throw_if(validate(config), "mesh");
    if (!(map.voxel_size > 0.0f) || !std::isfinite(map.voxel_size))
        throw common::ConfigError("mesh.voxel_size", "must be > 0 (the local map's voxel size)");
    MeshChunk c;
    c.local_map_id = map.id;
    c.revision = map.revision;
    c.segment = map.segment;
    c.T_odom_anchor = map.T_odom_anchor;
    c.T_anchor_grid = map.T_anchor_grid;
    c.voxel_size = map.voxel_size;
    c.cell_size = config.ownership_cell * double(map.voxel_size);
    c.voxels = surface_voxels(map.voxels, config, &c.voxels_left);

    // Ownership cells and the bounding sphere (anchor frame) of the voxels' cells.
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (const SurfaceVoxel& v : c.voxels) {
        const Eigen::Vector3d p = v.centre.cast<double>();
        c.cells.insert(cell_key(p, c.cell_size));
        const Eigen::Vector3d a = map.T_anchor_grid * p;
        lo = lo.cwiseMin(a);
        hi = hi.cwiseMax(a);
    }
    if ((hi - lo).minCoeff() >= 0.0) {
        c.centre = 0.5 * (lo + hi);
        // The cells reach up to a cell diagonal beyond the voxel centres, the surface a support.
        c.radius = 0.5 * (hi - lo).norm() + c.cell_size * std::sqrt(3.0) +
                   config.support * double(map.voxel_size);
    }
    return c;
}

MeshChunk make_chunk(const common::LocalMapData& map, const MeshConfig& config) {
    MeshChunk c = prepare_chunk(map, config);
    c.mesh = transformed(mesh_surface(c.voxels, c.voxel_size, config, &c.stats), c.T_anchor_grid);
    c.stats.voxels_left = c.voxels_left;
    c.complete = true;
    return c;
}

void mesh_cells(MeshChunk& c, const std::unordered_set<std::uint64_t>& cells,
                const MeshConfig& config) {
    std::vector<SurfaceVoxel> chosen;
    chosen.reserve(c.voxels.size());
    for (const SurfaceVoxel& v : c.voxels)
        if (cells.count(cell_key(v.centre.cast<double>(), c.cell_size))) chosen.push_back(v);
    c.mesh = transformed(mesh_surface(chosen, c.voxel_size, config, &c.stats), c.T_anchor_grid);
    c.stats.voxels_left = c.voxels_left;
    c.meshed_cells = cells;
    c.complete = false;
}

}  // namespace ltm::mesh
