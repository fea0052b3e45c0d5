#include "registration/core/voxel_grid.hpp"

namespace ltm::registration {

VoxelGrid::VoxelGrid(double voxel_size, const VoxelConfig& config)
    : voxel_size_(voxel_size), inv_voxel_size_(float(1.0 / voxel_size)), config_(config) {}

void VoxelGrid::begin_pass() {
    ++pass_;
    touched_.clear();
    pending_.clear();
}

void VoxelGrid::absorb_pending(double stamp) {
    constexpr std::size_t kAhead = 8;  // prefetch distance: hides the hash's cache misses
    VoxelKey last_key = ~VoxelKey(0);  // consecutive points often share a voxel
    std::uint32_t i = 0;
    const float g = float(voxel_size_);
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // of the voxel last_key (its sums' origin)
    for (std::size_t k = 0; k < pending_.size(); ++k) {
        if (k + kAhead < pending_.size()) hash_.prefetch(pending_[k + kAhead].key);
        const Pending& p = pending_[k];
        if (p.key != last_key) {
            const auto [index, inserted] = hash_.insert(p.key, std::uint32_t(keys_.size()));
            if (inserted) {
                keys_.push_back(p.key);
                surfels_.emplace_back();
                records_.emplace_back();
                records_.back().created = stamp;
            }
            i = index;
            last_key = p.key;
            centre = (unpack_key(p.key).cast<float>().array() + 0.5f).matrix() * g;
        }
        VoxelRecord& r = records_[i];
        r.sums.add(p.point - centre);
        if (r.last_scan != pass_) {
            r.last_scan = pass_;
            touched_.push_back(i);
        }
    }
}

void VoxelGrid::end_pass(const Eigen::Vector3f& sensor, double stamp) {
    for (const std::uint32_t i : touched_) {
        VoxelRecord& r = records_[i];
        ++r.observations;
        r.last_seen = stamp;
        const std::uint32_t was_usable = surfels_[i].usable;
        update_surfel(config_, float(voxel_size_), cell_centre(keys_[i]), sensor, r, surfels_[i]);
        if (surfels_[i].usable != was_usable) set_usable_tag(i);
    }
}

void VoxelGrid::copy_voxel(const VoxelGrid& other, std::size_t j, VoxelKey key) {
    const auto [index, inserted] = hash_.insert(key, std::uint32_t(keys_.size()));
    (void)index;
    if (!inserted) return;
    keys_.push_back(key);
    records_.push_back(other.records_[j]);
    records_.back().last_scan = 0;
    Surfel s = other.surfels_[j];
    s.centre += cell_centre(key) - other.cell_centre(other.keys_[j]);
    surfels_.push_back(s);
    if (s.usable) set_usable_tag(surfels_.size() - 1);
}

std::size_t VoxelGrid::usable_voxels() const {
    std::size_t n = 0;
    for (const Surfel& s : surfels_) n += s.usable;
    return n;
}

std::size_t VoxelGrid::memory_bytes() const {
    return hash_.memory_bytes() + keys_.capacity() * sizeof(VoxelKey) +
           surfels_.capacity() * sizeof(Surfel) + records_.capacity() * sizeof(VoxelRecord) +
           touched_.capacity() * sizeof(std::uint32_t) + pending_.capacity() * sizeof(Pending);
}

}  // namespace ltm::registration
