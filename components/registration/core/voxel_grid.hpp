#pragma once
// A hash of occupied voxels with running statistics (METHOD.md Eq. 1, 2): the data structure of a
// local map at one resolution. Coordinates are in the grid's own frame; voxel v covers
// [v * size, (v + 1) * size). Parallel arrays indexed by voxel: keys, surfels (hot, read by
// registration), records (cold: sums and life record).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "registration/core/registration_config.hpp"
#include "registration/core/voxel.hpp"
#include "registration/core/voxel_hash.hpp"

namespace ltm::registration {

class VoxelGrid {
  public:
    VoxelGrid(double voxel_size, const VoxelConfig& config);

    // The grid of a local map's plain data (its grid frame), voxel for voxel: keys, centres,
    // normals, planarity, stability and life records exactly as stored. A voxel is usable when it
    // has a unit normal and planarity >= min_planarity. The data has no second moments, so each
    // voxel's sums are rebuilt from its point count, centre, normal and planarity (a covariance
    // with that normal and planarity, spread over the cell in the plane): further integration
    // weighs the stored voxel by its point count. Voxels whose index is out of the key range or
    // whose centre is not finite are left out and counted in *skipped.
    static VoxelGrid from_data(const common::LocalMapData& data, const VoxelConfig& config,
                               double min_planarity, std::size_t* skipped = nullptr);

    // The voxels as plain data (the inverse of from_data): index, centre, normal (zero unless
    // usable), point count, planarity, stability and life record (health from it:
    // common::life_health).
    std::vector<common::VoxelData> to_data() const;

    // A grid of `factor` times the voxel size whose voxels hold the merged sums of this grid's
    // voxels (moments add exactly), with centres, normals and planarity computed from them.
    VoxelGrid coarsened(int factor, const VoxelConfig& config) const;

    double voxel_size() const { return voxel_size_; }

    // Absorbs the points of one scan taken from `sensor` at `stamp` into their voxels (those for
    // which keep(point) is true), then refreshes the touched voxels' centre, normal, stability and
    // life record. Returns how many points were absorbed.
    template <class Keep>
    std::size_t integrate(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& sensor,
                          double stamp, Keep&& keep) {
        begin_pass();
        for (const Eigen::Vector3f& p : points) {
            Eigen::Vector3i v;
            if (!keep(p) || !voxel_coords(p, inv_voxel_size_, &v)) continue;
            pending_.push_back({p, pack_key(v.x(), v.y(), v.z())});
        }
        absorb_pending(stamp);
        end_pass(sensor, stamp);
        return pending_.size();
    }

    // Copies the voxels of `other` (same voxel size) shifted by `offset` voxels, for which
    // keep(cell centre in this grid) is true; voxels already present keep their own statistics.
    template <class Keep>
    void seed_from(const VoxelGrid& other, const Eigen::Vector3i& offset, Keep&& keep) {
        for (std::size_t j = 0; j < other.size(); ++j) {
            const Eigen::Vector3i v = unpack_key(other.keys_[j]) + offset;
            const VoxelKey key = pack_key(v.x(), v.y(), v.z());
            if (keep(cell_centre(key))) copy_voxel(other, j, key);
        }
    }

    // Calls f(voxel index) for each occupied voxel of the 3x3x3 block around p's voxel.
    template <class F>
    void for_each_neighbour(const Eigen::Vector3f& p, F&& f) const {
        Eigen::Vector3i v;
        if (!voxel_coords(p, inv_voxel_size_, &v)) return;
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const std::uint32_t i =
                        hash_.find(pack_key(v.x() + dx, v.y() + dy, v.z() + dz));
                    if (i != VoxelHash::kNone) f(i);
                }
            }
        }
    }

    // The usable voxels (Surfel::usable) of the 3x3x3 block around p's voxel, in the order of
    // for_each_neighbour, written to out (at most 27); returns how many. Branch-free over the
    // block (whether a neighbour is there and usable is as likely as not: mispredicted branches
    // were much of the cost), and without reading the surfels: a voxel's usable flag is mirrored
    // in its hash slot's tag (set wherever a surfel's flag is written, see set_usable_tag).
    int usable_neighbours(const Eigen::Vector3f& p, std::uint32_t* out) const {
        Eigen::Vector3i v;
        if (!voxel_coords(p, inv_voxel_size_, &v)) return 0;
        VoxelKey keys[27];
        int n = 0;
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    keys[n] = pack_key(v.x() + dx, v.y() + dy, v.z() + dz);
                    hash_.prefetch(keys[n++]);
                }
            }
        }
        int count = 0;
        for (int k = 0; k < 27; ++k) {
            const std::uint32_t i = hash_.find_tagged(keys[k]);
            out[count] = i;
            count += int(i != VoxelHash::kNone);
        }
        return count;
    }

    // The key of p's voxel; false when p is out of the key range.
    bool key_of(const Eigen::Vector3f& p, VoxelKey* key) const {
        Eigen::Vector3i v;
        if (!voxel_coords(p, inv_voxel_size_, &v)) return false;
        *key = pack_key(v.x(), v.y(), v.z());
        return true;
    }
    // Index of the voxel with these integer coordinates, or VoxelHash::kNone.
    std::uint32_t find(const Eigen::Vector3i& v) const {
        return hash_.find(pack_key(v.x(), v.y(), v.z()));
    }
    Eigen::Vector3f cell_centre(VoxelKey key) const {
        return (unpack_key(key).cast<float>().array() + 0.5f).matrix() * float(voxel_size_);
    }

    std::size_t size() const { return keys_.size(); }
    bool empty() const { return keys_.empty(); }
    const std::vector<VoxelKey>& keys() const { return keys_; }
    const std::vector<Surfel>& surfels() const { return surfels_; }
    const std::vector<VoxelRecord>& records() const { return records_; }
    std::size_t usable_voxels() const;
    std::size_t memory_bytes() const;

  private:
    struct Pending {
        Eigen::Vector3f point;
        VoxelKey key;
    };
    void begin_pass();
    void absorb_pending(double stamp);
    void end_pass(const Eigen::Vector3f& sensor, double stamp);
    void copy_voxel(const VoxelGrid& other, std::size_t j, VoxelKey key);
    // The hash slot's tag of voxel i mirrors surfels_[i].usable (usable_neighbours reads it).
    void set_usable_tag(std::size_t i) { hash_.set_tag(keys_[i], surfels_[i].usable); }
    // Appends a voxel that is not present yet; false when the key is taken.
    bool insert_voxel(VoxelKey key, const Surfel& surfel, const VoxelRecord& record);

    double voxel_size_;
    float inv_voxel_size_;
    VoxelConfig config_;
    std::uint32_t pass_ = 0;  // integration pass counter (touched-voxel bookkeeping)
    VoxelHash hash_;
    std::vector<VoxelKey> keys_;
    std::vector<Surfel> surfels_;
    std::vector<VoxelRecord> records_;
    std::vector<std::uint32_t> touched_;  // voxels of the current pass
    std::vector<Pending> pending_;        // points of the current pass with their keys
};

}  // namespace ltm::registration
