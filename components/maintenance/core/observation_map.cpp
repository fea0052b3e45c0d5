#include "maintenance/core/observation_map.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace ltm::maintenance {

ObservationMap::ObservationMap(const MaintenanceConfig& config, const Eigen::Vector2i& region)
    : config_(config),
      region_(region),
      voxel_size_(float(config.voxel_size)),
      inv_voxel_size_(1.0f / float(config.voxel_size)) {}

std::uint32_t ObservationMap::insert(registration::VoxelKey key, double map_time,
                                     std::uint32_t session) {
    const auto [i, inserted] = hash_.insert(key, std::uint32_t(keys_.size()));
    if (inserted) {
        keys_.push_back(key);
        ObservedVoxel v;
        v.created = map_time;
        v.last_point = map_time;
        v.session = session;
        voxels_.push_back(std::move(v));
        last_scan_.push_back(0);
    }
    return i;
}

void ObservationMap::add_points(const std::vector<Eigen::Vector3f>& points, double map_time,
                                std::uint32_t session) {
    ++pass_;
    for (const Eigen::Vector3f& p : points) {
        Eigen::Vector3i c;
        if (!p.allFinite() || !registration::voxel_coords(p, inv_voxel_size_, &c)) continue;
        const std::uint32_t i =
            insert(registration::pack_key(c.x(), c.y(), c.z()), map_time, session);
        ObservedVoxel& v = voxels_[i];
        const Eigen::Vector3f q =
            p - (c.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_;
        if (v.sums.weight < 64.0f) v.sums.add(q);  // enough for a centre and a normal
        if (last_scan_[i] != pass_) {
            last_scan_[i] = pass_;
            v.last_point = std::max(v.last_point, map_time);
        }
    }
}

JudgeCounts ObservationMap::judge(const View& view) {
    JudgeCounts counts;
    const Eigen::Isometry3f T_sensor_world = view.T_world_sensor.inverse().cast<float>();
    const Eigen::Vector3f sensor = view.T_world_sensor.translation().cast<float>();
    const float max_range_sq = float(config_.max_range * config_.max_range);
    const auto slot = std::int32_t(std::floor(view.map_time / config_.slot));
    const float half_diagonal = 0.87f * voxel_size_;
    for (std::size_t i = 0; i < keys_.size(); ++i) {
        const Eigen::Vector3f c = cell_centre(std::uint32_t(i));
        if ((c - sensor).squaredNorm() > max_range_sq) continue;
        ++counts.voxels;
        const Eigen::Vector3f p = T_sensor_world * c;
        const float margin = float(config_.free_margin) + half_diagonal +
                             float(config_.free_margin_per_m) * p.norm();
        ObservedVoxel& v = voxels_[i];
        switch (view.image.classify(p, voxel_size_, margin)) {
            case Visibility::kSurface:
                add_to_histogram(v.hits, slot, 1, std::size_t(config_.max_slots));
                ++counts.hit;
                break;
            case Visibility::kFree:
                add_to_histogram(v.free, slot, 1, std::size_t(config_.max_slots));
                ++counts.free;
                break;
            case Visibility::kOccluded:
                ++counts.occluded;
                break;
            case Visibility::kUnseen:
                ++counts.unseen;
                break;
        }
    }
    return counts;
}

std::uint32_t ObservationMap::find(const Eigen::Vector3f& p) const {
    Eigen::Vector3i c;
    if (!p.allFinite() || !registration::voxel_coords(p, inv_voxel_size_, &c)) return kNone;
    return hash_.find(registration::pack_key(c.x(), c.y(), c.z()));
}

Eigen::Vector3f ObservationMap::cell_centre(std::uint32_t i) const {
    return (registration::unpack_key(keys_[i]).cast<float>() + Eigen::Vector3f::Constant(0.5f)) *
           voxel_size_;
}

Eigen::Vector3f ObservationMap::centre(std::uint32_t i) const {
    const registration::VoxelSums& s = voxels_[i].sums;
    return cell_centre(i) + (s.weight > 0.0f ? s.mean() : Eigen::Vector3f::Zero());
}

Eigen::Vector3f ObservationMap::normal(std::uint32_t i) const {
    const registration::VoxelSums& s = voxels_[i].sums;
    if (s.weight < 3.0f) return Eigen::Vector3f::Zero();
    const Eigen::Matrix3d cov = s.covariance();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    const Eigen::Vector3d l = es.eigenvalues();
    if (!(l(1) > 4.0 * std::max(l(0), 0.0))) return Eigen::Vector3f::Zero();  // no plane
    return es.eigenvectors().col(0).cast<float>().normalized();
}

bool ObservationMap::restore(registration::VoxelKey key, ObservedVoxel voxel) {
    const auto [i, inserted] = hash_.insert(key, std::uint32_t(keys_.size()));
    if (!inserted) return false;
    keys_.push_back(key);
    voxels_.push_back(std::move(voxel));
    last_scan_.push_back(0);
    return i == keys_.size() - 1;
}

void ObservationMap::erase(const std::vector<bool>& remove) {
    std::size_t out = 0;
    for (std::size_t i = 0; i < keys_.size(); ++i) {
        if (i < remove.size() && remove[i]) continue;
        if (out != i) {
            keys_[out] = keys_[i];
            voxels_[out] = std::move(voxels_[i]);
            last_scan_[out] = last_scan_[i];
        }
        ++out;
    }
    keys_.resize(out);
    voxels_.resize(out);
    last_scan_.resize(out);
    hash_.clear();
    hash_.reserve(out);
    for (std::size_t i = 0; i < out; ++i) hash_.insert(keys_[i], std::uint32_t(i));
}

std::size_t ObservationMap::memory_bytes() const {
    std::size_t n = hash_.memory_bytes() + keys_.capacity() * sizeof(registration::VoxelKey) +
                    voxels_.capacity() * sizeof(ObservedVoxel) +
                    last_scan_.capacity() * sizeof(std::uint64_t);
    for (const ObservedVoxel& v : voxels_)
        n += (v.hits.capacity() + v.free.capacity()) * sizeof(SlotCount);
    return n;
}

}  // namespace ltm::maintenance
