#include "registration/core/voxel_hash.hpp"

#include <algorithm>

namespace ltm::registration {

void VoxelHash::clear() {
    std::fill(slots_.begin(), slots_.end(), Slot{kEmpty, 0, 0});
    size_ = 0;
}

void VoxelHash::reserve(std::size_t n) {
    std::size_t capacity = 16;
    while (capacity < 2 * n) capacity *= 2;
    if (capacity > slots_.size()) rehash(capacity);
}

void VoxelHash::rehash(std::size_t capacity) {
    std::vector<Slot> old;
    old.swap(slots_);
    slots_.assign(capacity, Slot{kEmpty, 0, 0});
    mask_ = capacity - 1;
    shift_ = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
    size_ = 0;
    for (const Slot& s : old) {
        if (s.key == kEmpty) continue;
        insert(s.key, s.value);
        if (s.tag != 0) set_tag(s.key, s.tag);
    }
}

}  // namespace ltm::registration
