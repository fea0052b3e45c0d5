#include "localisation/core/map_features.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace ltm::localisation {

namespace {

constexpr double kColumnSize = 8.0;  // [m] cell of the 2-D index of voxel centres

std::uint64_t grid_key(std::int64_t ix, std::int64_t iy) {
    return (std::uint64_t(ix + (1 << 30)) << 32) | std::uint64_t(iy + (1 << 30));
}

// A lattice point's cell of a grid of `step` (the point is at a multiple of step, or anywhere).
std::uint64_t lattice_key(double x, double y, double step) {
    return grid_key(std::lround(x / step), std::lround(y / step));
}

// The voxel centres in 8 m columns, for the centres within a radius of a point.
class Columns {
  public:
    explicit Columns(const std::vector<common::VoxelData>& voxels) : voxels_(voxels) {
        for (std::uint32_t i = 0; i < voxels.size(); ++i) {
            const Eigen::Vector3f& c = voxels[i].centre;
            cells_[key(c.x(), c.y())].push_back(i);
        }
    }
    std::vector<Eigen::Vector3f> near(const Eigen::Vector3d& p, double radius) const {
        std::vector<Eigen::Vector3f> out;
        const double r2 = radius * radius;
        const int reach = int(std::ceil(radius / kColumnSize));
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                const auto it =
                    cells_.find(key(p.x() + dx * kColumnSize, p.y() + dy * kColumnSize));
                if (it == cells_.end()) continue;
                for (std::uint32_t i : it->second) {
                    const Eigen::Vector3f& c = voxels_[i].centre;
                    const double ex = c.x() - p.x(), ey = c.y() - p.y();
                    if (ex * ex + ey * ey <= r2) out.push_back(c);
                }
            }
        }
        return out;
    }

  private:
    static std::uint64_t key(double x, double y) {
        return grid_key(std::int64_t(std::floor(x / kColumnSize)),
                        std::int64_t(std::floor(y / kColumnSize)));
    }
    const std::vector<common::VoxelData>& voxels_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace

places::LocalFeatures make_map_features(const std::vector<common::VoxelData>& voxels,
                                        const LocalisationMapConfig& config,
                                        const std::vector<Eigen::Vector3d>* around, double near) {
    const double cell = config.feature_cell;
    const double half_diagonal = cell * 0.7072;
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
    const Columns columns(voxels);
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
            columns.near(centre, half_diagonal + config.features.radius), tile, centre,
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
