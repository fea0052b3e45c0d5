#pragma once
// A voxel's view history in 42 bytes: on one timeline of map-time slots, how many views hit it
// (a return at it) and how many saw through it (a return beyond it), in at most kCapacity
// entries, and the exact slots of its first and last hit (their span tells a passer-by from a
// parked car, and a few hits from a static voxel: merged entries would shorten it).
// When a new slot would make one entry too many, the two closest neighbouring entries merge at
// their view-weighted mean slot (the views' mass and mean are kept, the shape coarsens evenly, as
// the separate hit and free histograms did before); "closest" weighs the gap by how much the
// pair's hit fractions differ (1 + 4 d), so entries of one kind merge first; the oldest of equal
// pairs.
//
// Why one timeline for both: a view says hit or free about the voxel, never both, so the two
// histories share their times; one timeline stores each time once (ObservationMap's per-voxel
// state went 640 -> under 100 bytes: components/maintenance/README.md).
//
// Packed: the anchor (int32: the first hit's slot, or the first view's while there is no hit), the
// last hit as a uint16 offset from it (saturating at 65535 slots: 9 h at 0.5 s, far beyond any
// span the decisions compare), then per entry a signed 24-bit offset from the anchor (+-48 days
// of map time at 0.5 s slots; farther views are put on the last slot it holds) and two 12-bit
// counts. An entry with no views ends the list. When a count would pass 4095, every count of the
// voxel is halved (rounded up): the shape is kept, only voxels with thousands of views lose
// absolute counts.
#include <array>
#include <cstdint>

#include "maintenance/core/time_distribution.hpp"

namespace ltm::maintenance {

class VoxelHistory {
  public:
    static constexpr int kCapacity = 6;
    static constexpr std::int64_t kMaxOffset = (std::int64_t(1) << 23) - 1;
    static constexpr std::uint32_t kMaxCount = 4095;
    static constexpr std::uint32_t kMaxSpan = 65535;

    struct Entry {
        std::int32_t slot = 0;
        std::uint32_t hits = 0, free = 0;
    };
    // Decoded entries, in increasing slot order (one more than kCapacity while adding), and the
    // first and last hit (meaningful when some entry has hits).
    struct Entries {
        std::array<Entry, kCapacity + 1> e;
        int n = 0;
        std::int32_t first_hit = 0, last_hit = 0;
    };

    // One view in `slot`: a hit or a free view. At most max_entries (2..kCapacity) are kept.
    void add(std::int32_t slot, bool hit, int max_entries);

    Entries entries() const;
    // Replaces the entries (in increasing slot order, each with views, at most kCapacity; the
    // file reader checks this first). Counts above kMaxCount are halved as above; slots farther
    // than kMaxOffset from the anchor are clamped.
    void assign(Entries entries);

    bool empty() const;
    // The hit and the free views as slot histograms (the change decisions read these).
    SlotHistogram hit_histogram() const;
    SlotHistogram free_histogram() const;
    // The hit histogram and every view's (hits and free views summed by slot) into the given
    // ones (cleared first; their room is reused: a pass judges every voxel of a region).
    void histograms(SlotHistogram* hits, SlotHistogram* views) const;
    // Slots from the first hit to the last (0 without hits), at most kMaxSpan.
    std::uint32_t hit_span() const;

  private:
    static constexpr int kHeadBytes = 6, kEntryBytes = 6;
    std::array<std::uint8_t, kHeadBytes + kCapacity * kEntryBytes> bytes_{};
};

// Merges the closest neighbouring entries (as above) until at most max_entries are left.
void merge_closest(VoxelHistory::Entries& entries, int max_entries);

}  // namespace ltm::maintenance
