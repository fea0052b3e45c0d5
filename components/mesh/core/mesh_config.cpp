#include "mesh/core/mesh_config.hpp"

#include <algorithm>

namespace ltm::mesh {

std::optional<common::ConfigProblem> validate(const MeshConfig& config) {
    common::ConfigChecker k;
    MeshConfig c = config;
    visit_fields(c, "", k);
    k.require(c.truncation == 0.0 || c.grid_size == 0.0 || c.truncation >= c.grid_size,
              "truncation", "must be at least grid_size (or 0: 2 grid cells)");
    return k.problem();
}

double effective_grid_size(const MeshConfig& config, double voxel_size) {
    return config.grid_size > 0.0 ? config.grid_size : voxel_size / 3.0;
}

double effective_truncation(const MeshConfig& config, double voxel_size) {
    const double g = effective_grid_size(config, voxel_size);
    return config.truncation > 0.0 ? std::max(config.truncation, g) : 2.0 * g;
}

}  // namespace ltm::mesh
