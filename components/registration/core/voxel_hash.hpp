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

// floor(x) when it is within the key range (|floor(x)| < kVoxelKeyLimit), else false (NaN too).
// The same as std::floor and a range check, in a few instructions: floor(x) < limit exactly when
// x < limit, and floor(x) > -limit exactly when x >= 1 - limit (the limits are integers); within
// that range a float converts to an int exactly, and truncation rounds up below zero.
inline bool floor_in_key_range(float x, std::int32_t* out) {
    if (!(x >= float(1 - kVoxelKeyLimit) && x < float(kVoxelKeyLimit))) return false;
    const std::int32_t t = std::int32_t(x);
    *out = t - std::int32_t(float(t) > x);
    return true;
}

// Integer voxel coordinates of p on a grid of edge `inv_size`^-1; false when out of key range.
inline bool voxel_coords(const Eigen::Vector3f& p, float inv_size, Eigen::Vector3i* v) {
    std::int32_t x, y, z;
    if (!floor_in_key_range(p.x() * inv_size, &x) || !floor_in_key_range(p.y() * inv_size, &y) ||
        !floor_in_key_range(p.z() * inv_size, &z)) {
        return false;
    }
    *v = Eigen::Vector3i(x, y, z);
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
                s.tag = 0;
                ++size_;
                return {value, true};
            }
            i = (i + 1) & mask_;
        }
    }

    // A tag per entry (0 on insertion), kept in the slot's otherwise unused bytes: a look-up that
    // filters on it (find_tagged) reads no other memory. set_tag: the key must be present.
    void set_tag(VoxelKey key, std::uint32_t tag) {
        std::size_t i = slot_of(key);
        while (slots_[i].key != key) i = (i + 1) & mask_;
        slots_[i].tag = tag;
    }
    // The value stored for key when its tag is not 0, else kNone.
    std::uint32_t find_tagged(VoxelKey key) const { return find_tagged_from(slot_of(key), key); }

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
        std::uint32_t tag;
    };
    std::size_t slot_of(VoxelKey key) const {
        return std::size_t((key * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
    }
    void rehash(std::size_t capacity);
    std::uint32_t find_tagged_from(std::size_t i, VoxelKey key) const {
        for (;;) {
            const Slot& s = slots_[i];
            if (s.key == key) return s.tag != 0 ? s.value : kNone;
            if (s.key == kEmpty) return kNone;
            i = (i + 1) & mask_;
        }
    }

    std::vector<Slot> slots_;
    std::size_t mask_ = 0, size_ = 0;
    int shift_ = 64;
};

}  // namespace ltm::registration
