#pragma once
// Open-addressing hash from a packed voxel key to a 32-bit index (Eq. 1). Data-oriented: one flat
// array of 16-byte slots, linear probing, no per-entry allocation, no deletion (a local map only
// grows; it is dropped as a whole).
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace ltm::registration {

// A voxel's integer coordinates packed into 64 bits, 21 bits an axis (range +-2^20 voxels).
using VoxelKey = std::uint64_t;
constexpr std::int32_t kVoxelKeyLimit = (1 << 20) - 1;

inline VoxelKey pack_key(std::int32_t x, std::int32_t y, std::int32_t z) {
    constexpr std::uint64_t bias = 1u << 20, mask = (1u << 21) - 1;
    return (std::uint64_t(x + bias) & mask) | ((std::uint64_t(y + bias) & mask) << 21) |
           ((std::uint64_t(z + bias) & mask) << 42);
}

inline Eigen::Vector3i unpack_key(VoxelKey k) {
    constexpr std::int64_t bias = 1 << 20, mask = (1 << 21) - 1;
    return {int(std::int64_t(k & mask) - bias), int(std::int64_t((k >> 21) & mask) - bias),
            int(std::int64_t((k >> 42) & mask) - bias)};
}

// Integer voxel coordinates of p on a grid of edge `inv_size`^-1; false when out of key range.
inline bool voxel_coords(const Eigen::Vector3f& p, float inv_size, Eigen::Vector3i* v) {
    const float x = std::floor(p.x() * inv_size), y = std::floor(p.y() * inv_size),
                z = std::floor(p.z() * inv_size);
    constexpr float lim = float(kVoxelKeyLimit);
    if (!(std::abs(x) < lim && std::abs(y) < lim && std::abs(z) < lim)) return false;
    *v = Eigen::Vector3i(int(x), int(y), int(z));
    return true;
}

class VoxelHash {
  public:
    static constexpr std::uint32_t kNone = 0xffffffffu;

    explicit VoxelHash(std::size_t expected = 1024) { reserve(expected); }

    std::uint32_t find(VoxelKey key) const {
        std::size_t i = slot_of(key);
        for (;;) {
            const Slot& s = slots_[i];
            if (s.key == key) return s.value;
            if (s.key == kEmpty) return kNone;
            i = (i + 1) & mask_;
        }
    }

    // The value stored for key, or `value` after inserting it. second: inserted.
    std::pair<std::uint32_t, bool> insert(VoxelKey key, std::uint32_t value) {
        if ((size_ + 1) * 2 > slots_.size()) rehash(slots_.size() * 2);
        std::size_t i = slot_of(key);
        for (;;) {
            Slot& s = slots_[i];
            if (s.key == key) return {s.value, false};
            if (s.key == kEmpty) {
                s.key = key;
                s.value = value;
                ++size_;
                return {value, true};
            }
            i = (i + 1) & mask_;
        }
    }

    // Hints the cache that `key` is about to be looked up.
    void prefetch(VoxelKey key) const { __builtin_prefetch(&slots_[slot_of(key)]); }

    std::size_t size() const { return size_; }
    // Removes every entry; keeps the capacity (no allocation on the next frame).
    void clear();
    // Capacity for n entries at a load of at most one half.
    void reserve(std::size_t n);
    std::size_t memory_bytes() const { return slots_.capacity() * sizeof(Slot); }

  private:
    static constexpr VoxelKey kEmpty = ~VoxelKey(0);  // never a packed key (bit 63 unused)
    struct Slot {
        VoxelKey key;
        std::uint32_t value;
    };
    std::size_t slot_of(VoxelKey key) const {
        return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
    }
    void rehash(std::size_t capacity);

    std::vector<Slot> slots_;
    std::size_t mask_ = 0, size_ = 0;
    int shift_ = 64;
};

}  // namespace ltm::registration
