#pragma once
// Open-addressing index from a packed voxel key to the voxel's number, 4 bytes a bucket: the
// keys live with the voxels (a key_of(number) function reads them), so the index holds numbers
// only (registration::VoxelHash keeps 16-byte key/value slots at a load of at most one half: 32 to
// 64 bytes a voxel). Linear probing; the bucket of a key is a multiply-shift of its hash onto
// any bucket count, so the table grows by 1.6x (load 0.5 to 0.8) instead of doubling.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "registration/core/voxel_hash.hpp"

namespace ltm::maintenance {

class VoxelIndex {
  public:
    static constexpr std::uint32_t kNone = 0xffffffffu;

    // The number stored for key, or kNone.
    template <class KeyOf>
    std::uint32_t find(registration::VoxelKey key, const KeyOf& key_of) const {
        if (buckets_.empty()) return kNone;
        for (std::size_t b = bucket_of(key);; b = b + 1 == buckets_.size() ? 0 : b + 1) {
            const std::uint32_t i = buckets_[b];
            if (i == kNone) return kNone;
            if (key_of(i) == key) return i;
        }
    }

    // Adds number i for key, which must not be in the index (find() first); key_of(i) == key.
    // Numbers are 0..size()-1 in insertion order: a growing table re-places them through key_of.
    template <class KeyOf>
    void insert(registration::VoxelKey key, std::uint32_t i, const KeyOf& key_of) {
        if ((size_ + 1) * 5 > buckets_.size() * 4) rebuild(size_ + 1, key_of, size_);
        place(key, i);
        ++size_;
    }

    // Room for n numbers at a load of 0.625, holding numbers 0..indexed-1 (insert() growing).
    template <class KeyOf>
    void rebuild(std::size_t n, const KeyOf& key_of, std::size_t indexed) {
        buckets_.assign(std::max<std::size_t>(16, n * 8 / 5), kNone);
        buckets_.shrink_to_fit();
        size_ = 0;
        for (std::size_t i = 0; i < indexed; ++i, ++size_)
            place(key_of(std::uint32_t(i)), std::uint32_t(i));
    }
    // The index of voxels 0..n-1 (after they were erased or reordered).
    template <class KeyOf>
    void rebuild(std::size_t n, const KeyOf& key_of) {
        rebuild(n, key_of, n);
    }

    std::size_t size() const { return size_; }
    std::size_t memory_bytes() const { return buckets_.capacity() * sizeof(std::uint32_t); }

  private:
    std::size_t bucket_of(registration::VoxelKey key) const {
        const std::uint64_t h = (key ^ (key >> 29)) * 0x9E3779B97F4A7C15ull;
        return std::size_t(((h >> 32) * std::uint64_t(buckets_.size())) >> 32);
    }
    void place(registration::VoxelKey key, std::uint32_t i) {
        std::size_t b = bucket_of(key);
        while (buckets_[b] != kNone) b = b + 1 == buckets_.size() ? 0 : b + 1;
        buckets_[b] = i;
    }

    std::vector<std::uint32_t> buckets_;
    std::size_t size_ = 0;
};

}  // namespace ltm::maintenance
