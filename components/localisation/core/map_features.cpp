#include "localisation/core/map_features.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "localisation/core/voxel_columns.hpp"

namespace ltm::localisation {

namespace {

std::uint64_t grid_key(std::int64_t ix, std::int64_t iy) {
    return (std::uint64_t(ix + (1 << 30)) << 32) | std::uint64_t(iy + (1 << 30));
}

// A lattice point's cell of a grid of `step` (the point is at a multiple of step, or anywhere).
std::uint64_t lattice_key(double x, double y, double step) {
    return grid_key(std::lround(x / step), std::lround(y / step));
}

}  // namespace

places::LocalFeatures make_map_features(const std::vector<common::VoxelData>& voxels,
                                        const LocalisationMapConfig& config,
                                        const std::vector<Eigen::Vector3d>* around, double near) {
    const double cell = config.feature_cell;
    const double half_diagonal = cell * kFeatureCellHalfDiagonal;
    // The cells holding a voxel (their order: the hash map's, as every load has made them).
    std::unordered_map<std::uint64_t, Eigen::Vector2d> cells;
    for (const common::VoxelData& v : voxels) {
        const double cx = (std::floor(v.centre.x() / cell) + 0.5) * cell;
        const double cy = (std::floor(v.centre.y() / cell) + 0.5) * cell;
        cells.emplace(lattice_key(cx, cy, cell), Eigen::Vector2d(cx, cy));
    }
    const double near2 = near * near;
    const auto wanted = [&](const Eigen::Vector2d& c) {
        return !around || std::any_of(around->begin(), around->end(), [&](const auto& p) {
            return (c - p.template head<2>()).squaredNorm() <= near2;
        });
    };
    const VoxelColumns columns(voxels);
    const double spacing = config.features.sample_spacing;
    places::LocalFeatures features;
    features.sample_spacing = spacing;
    // Every lattice point of a tile (a thinned lattice would break the matches' refinement).
    places::LocalFeatureConfig tile = config.features;
    tile.max_samples = std::max(tile.max_samples, int(std::pow(cell / spacing + 2.0, 2.0)) * 2);
    std::unordered_set<std::uint64_t> seen;
    for (const auto& [key, c] : cells) {
        if (!wanted(c)) continue;
        const Eigen::Vector3d centre(c.x(), c.y(), 0.0);
        const places::LocalFeatures f = places::make_local_features(
            columns.centres_near(centre, half_diagonal + config.features.radius), tile, centre,
            half_diagonal);
        for (std::size_t i = 0; i < f.size(); ++i) {
            const Eigen::Vector3d& p = f.positions[i];
            if (std::abs(p.x() - c.x()) > 0.5 * cell || std::abs(p.y() - c.y()) > 0.5 * cell)
                continue;  // another cell's sample
            if (!seen.insert(lattice_key(p.x(), p.y(), spacing)).second) continue;
            features.positions.push_back(p);
            features.descriptors.push_back(f.descriptors[i]);
        }
    }
    return features;
}

}  // namespace ltm::localisation
