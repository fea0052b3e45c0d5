// VoxelGrid from plain local-map data, and coarse grids from fine ones (voxel_grid.hpp).
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "common/core/voxel_health.hpp"
#include "registration/core/voxel_grid.hpp"

namespace ltm::registration {
namespace {

// Sums of `weight` points with mean `mean` (relative to the cell centre) and covariance `cov`.
VoxelSums sums_of(float weight, const Eigen::Vector3f& mean, const Eigen::Matrix3f& cov) {
    VoxelSums s;
    s.weight = weight;
    s.sum = weight * mean;
    const Eigen::Matrix3f m2 = weight * (cov + mean * mean.transpose());
    s.sum_sq << m2(0, 0), m2(0, 1), m2(0, 2), m2(1, 1), m2(1, 2), m2(2, 2);
    return s;
}

}  // namespace

bool VoxelGrid::insert_voxel(VoxelKey key, const Surfel& surfel, const VoxelRecord& record) {
    const auto [index, inserted] = hash_.insert(key, std::uint32_t(keys_.size()));
    (void)index;
    if (!inserted) return false;
    keys_.push_back(key);
    surfels_.push_back(surfel);
    records_.push_back(record);
    records_.back().last_scan = 0;
    if (surfel.usable) set_usable_tag(surfels_.size() - 1);
    return true;
}

VoxelGrid VoxelGrid::from_data(const common::LocalMapData& data, const VoxelConfig& config,
                               double min_planarity, std::size_t* skipped) {
    const double g =
        data.voxel_size > 0.0f && std::isfinite(data.voxel_size) ? double(data.voxel_size) : 1.0;
    VoxelGrid grid(g, config);
    // Room for every voxel at once: no doubling slack in a loaded map's grids (up to half of them).
    grid.hash_.reserve(data.voxels.size());
    grid.keys_.reserve(data.voxels.size());
    grid.surfels_.reserve(data.voxels.size());
    grid.records_.reserve(data.voxels.size());
    std::size_t left_out = 0;
    // In-plane spread of the rebuilt covariance: points uniform over the cell (g^2 / 12).
    const float spread = float(g * g / 12.0);
    for (const common::VoxelData& v : data.voxels) {
        if (!v.centre.allFinite() || (v.index.cwiseAbs().array() >= kVoxelKeyLimit).any()) {
            ++left_out;
            continue;
        }
        const VoxelKey key = pack_key(v.index.x(), v.index.y(), v.index.z());
        Surfel s;
        s.centre = v.centre;
        s.planarity = std::isfinite(v.planarity) ? v.planarity : 0.0f;
        s.stability = std::isfinite(v.stability) ? v.stability : 0.0f;
        const bool has_normal = v.normal.allFinite() && std::abs(v.normal.norm() - 1.0f) < 1e-2f;
        if (has_normal) {  // stored as given unless it needs normalising (exact round trip)
            s.normal = std::abs(v.normal.norm() - 1.0f) < 1e-6f ? v.normal : v.normal.normalized();
        }
        s.usable = has_normal && double(s.planarity) >= min_planarity ? 1u : 0u;
        VoxelRecord r;
        r.created = v.life.created;
        r.last_seen = v.life.last_seen;
        r.observations = v.life.observations;
        r.previous_normal = s.normal;
        const float weight = float(std::max<std::uint32_t>(v.point_count, 1));
        Eigen::Matrix3f cov = spread * Eigen::Matrix3f::Identity();
        if (has_normal) {
            const float across = (1.0f - std::clamp(s.planarity, 0.0f, 1.0f)) * spread;
            cov -= (spread - across) * s.normal * s.normal.transpose();
        }
        r.sums = sums_of(weight, s.centre - grid.cell_centre(key), cov);
        if (!grid.insert_voxel(key, s, r)) ++left_out;  // a repeated index: the first one stays
    }
    if (skipped) *skipped = left_out;
    return grid;
}

std::vector<common::VoxelData> VoxelGrid::to_data() const {
    std::vector<common::VoxelData> out(size());
    for (std::size_t i = 0; i < size(); ++i) {
        const Surfel& s = surfels_[i];
        const VoxelRecord& r = records_[i];
        common::VoxelData& v = out[i];
        v.index = unpack_key(keys_[i]);
        v.centre = s.centre;
        v.normal = s.usable ? s.normal : Eigen::Vector3f::Zero();
        v.point_count = std::uint32_t(std::lround(std::max(0.0f, r.sums.weight)));
        v.planarity = s.planarity;
        v.stability = s.stability;
        v.life.created = r.created;
        v.life.last_seen = r.last_seen;
        v.life.observations = r.observations;
        v.life.health = common::life_health(v.life);
    }
    return out;
}

VoxelGrid VoxelGrid::coarsened(int factor, const VoxelConfig& config) const {
    VoxelGrid coarse(voxel_size_ * factor, config);
    const auto floor_div = [factor](int a) {
        return a >= 0 ? a / factor : -((-a + factor - 1) / factor);
    };
    std::unordered_map<VoxelKey, VoxelSums> merged;  // absolute moments, coarse cell frame
    std::unordered_map<VoxelKey, VoxelRecord> life;
    std::vector<VoxelKey> order;
    for (std::size_t i = 0; i < size(); ++i) {
        const Eigen::Vector3i v = unpack_key(keys_[i]);
        const VoxelKey ck = pack_key(floor_div(v.x()), floor_div(v.y()), floor_div(v.z()));
        const VoxelSums& s = records_[i].sums;
        if (!(s.weight > 0.0f)) continue;
        // Move the fine voxel's moments from its cell centre to the coarse cell centre.
        const Eigen::Vector3f d = cell_centre(keys_[i]) - coarse.cell_centre(ck);
        const Eigen::Vector3f mean = s.mean() + d;
        const Eigen::Matrix3f cov = s.covariance().cast<float>();
        const VoxelSums shifted = sums_of(s.weight, mean, cov);
        auto [it, fresh] = merged.try_emplace(ck, shifted);
        VoxelRecord& rec = life[ck];
        if (fresh) {
            order.push_back(ck);
            rec.created = records_[i].created;
        } else {
            it->second.weight += shifted.weight;
            it->second.sum += shifted.sum;
            it->second.sum_sq += shifted.sum_sq;
            rec.created = std::min(rec.created, records_[i].created);
        }
        rec.last_seen = std::max(rec.last_seen, records_[i].last_seen);
        rec.observations = std::max(rec.observations, records_[i].observations);
    }
    for (const VoxelKey ck : order) {
        VoxelRecord r = life[ck];
        r.sums = merged[ck];
        Surfel s;
        // A normal's sign is arbitrary (IMLS aligns signs itself): orient towards +z, so the
        // result does not depend on the order of the fine voxels.
        update_surfel(config, float(coarse.voxel_size_), coarse.cell_centre(ck),
                      coarse.cell_centre(ck) + Eigen::Vector3f(0.0f, 0.0f, 1e3f), r, s);
        coarse.insert_voxel(ck, s, r);
    }
    return coarse;
}

}  // namespace ltm::registration
