#include "maintenance/core/voxel_history.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ltm::maintenance {

namespace {

// A pair whose hit fractions differ by d merges as if (1 + 4 d) times farther apart: entries of
// one kind (all hits, all seen through) merge first and a moving object's short run of hits
// keeps its own entry (site_sessions' session 0: DA of moving actors 78.9 % -> 81.6 %).
constexpr double kFractionWeight = 4.0;

std::uint32_t get(const std::uint8_t* p, int bytes) {
    std::uint32_t v = 0;
    for (int k = bytes; k-- > 0;) v = (v << 8) | p[k];
    return v;
}

void put(std::uint8_t* p, int bytes, std::uint32_t v) {
    for (int k = 0; k < bytes; ++k, v >>= 8) p[k] = std::uint8_t(v & 0xffu);
}

bool has_hits(const VoxelHistory::Entries& h) {
    for (int k = 0; k < h.n; ++k)
        if (h.e[std::size_t(k)].hits > 0) return true;
    return false;
}

}  // namespace

bool VoxelHistory::empty() const { return get(&bytes_[kHeadBytes + 3], 3) == 0; }

VoxelHistory::Entries VoxelHistory::entries() const {
    Entries out;
    const auto anchor = std::int32_t(get(&bytes_[0], 4));
    for (int k = 0; k < kCapacity; ++k) {
        const std::uint8_t* p = &bytes_[std::size_t(kHeadBytes + k * kEntryBytes)];
        const std::uint32_t counts = get(p + 3, 3);
        if (counts == 0) break;
        std::int32_t offset = std::int32_t(get(p, 3));
        if (offset & 0x800000) offset -= 0x1000000;  // sign of the 24-bit offset
        Entry& e = out.e[std::size_t(k)];
        e.slot = std::int32_t(std::int64_t(anchor) + offset);
        e.hits = counts & 0xfffu;
        e.free = counts >> 12;
        out.n = k + 1;
    }
    out.first_hit = anchor;
    out.last_hit = std::int32_t(std::int64_t(anchor) + get(&bytes_[4], 2));
    return out;
}

void VoxelHistory::assign(Entries h) {
    bytes_.fill(0);
    h.n = std::min(h.n, kCapacity);
    if (h.n == 0) return;
    std::uint32_t most = 0;
    for (int k = 0; k < h.n; ++k)
        most = std::max({most, h.e[std::size_t(k)].hits, h.e[std::size_t(k)].free});
    while (most > kMaxCount) {  // halve every count, rounded up: the shape is kept
        for (int k = 0; k < h.n; ++k) {
            h.e[std::size_t(k)].hits = (h.e[std::size_t(k)].hits + 1) / 2;
            h.e[std::size_t(k)].free = (h.e[std::size_t(k)].free + 1) / 2;
        }
        most = (most + 1) / 2;
    }
    const bool hits = has_hits(h);
    const std::int64_t anchor = hits ? h.first_hit : h.e[0].slot;
    put(&bytes_[0], 4, std::uint32_t(std::int32_t(anchor)));
    if (hits) {
        const std::int64_t span = std::int64_t(h.last_hit) - h.first_hit;
        put(&bytes_[4], 2, std::uint32_t(std::clamp<std::int64_t>(span, 0, kMaxSpan)));
    }
    for (int k = 0; k < h.n; ++k) {
        const Entry& e = h.e[std::size_t(k)];
        std::uint8_t* p = &bytes_[std::size_t(kHeadBytes + k * kEntryBytes)];
        const std::int64_t offset =
            std::clamp<std::int64_t>(std::int64_t(e.slot) - anchor, -kMaxOffset, kMaxOffset);
        put(p, 3, std::uint32_t(offset) & 0xffffffu);
        put(p + 3, 3, e.hits | (e.free << 12));
    }
}

void merge_closest(VoxelHistory::Entries& h, int max_entries) {
    max_entries = std::clamp(max_entries, 2, VoxelHistory::kCapacity);
    while (h.n > max_entries) {
        // Each entry's hit fraction once (each is in two neighbours' costs).
        std::array<double, VoxelHistory::kCapacity + 1> fraction;
        for (int j = 0; j < h.n; ++j) {
            const VoxelHistory::Entry& a = h.e[std::size_t(j)];
            fraction[std::size_t(j)] = double(a.hits) / std::max(1.0, double(a.hits) + a.free);
        }
        const auto cost = [&](int j) {
            const double gap =
                double(h.e[std::size_t(j + 1)].slot) - double(h.e[std::size_t(j)].slot);
            return gap * (1.0 + kFractionWeight * std::abs(fraction[std::size_t(j)] -
                                                           fraction[std::size_t(j + 1)]));
        };
        int k = 0;
        double best = cost(0);
        for (int j = 1; j + 1 < h.n; ++j) {
            const double c = cost(j);
            if (c < best) {
                best = c;
                k = j;
            }
        }
        VoxelHistory::Entry& a = h.e[std::size_t(k)];
        const VoxelHistory::Entry& b = h.e[std::size_t(k + 1)];
        const double wa = double(a.hits) + a.free, wb = double(b.hits) + b.free;
        const double mean = (wa * a.slot + wb * double(b.slot)) / std::max(wa + wb, 1.0);
        a.slot = std::int32_t(std::lround(mean));
        a.hits += b.hits;
        a.free += b.free;
        for (int j = k + 1; j + 1 < h.n; ++j) h.e[std::size_t(j)] = h.e[std::size_t(j + 1)];
        --h.n;
    }
}

void VoxelHistory::add(std::int32_t slot, bool hit, int max_entries) {
    Entries h = entries();
    if (h.n > 0) {  // within kMaxOffset of the anchor: farther views go to its edge
        const std::int64_t anchor = has_hits(h) ? h.first_hit : h.e[0].slot;
        slot =
            std::int32_t(std::clamp<std::int64_t>(slot, anchor - kMaxOffset, anchor + kMaxOffset));
    }
    if (hit) {
        const bool first = !has_hits(h);
        h.first_hit = first ? slot : std::min(h.first_hit, slot);
        h.last_hit = first ? slot : std::max(h.last_hit, slot);
    }
    int at = 0;
    while (at < h.n && h.e[std::size_t(at)].slot < slot) ++at;
    if (at < h.n && h.e[std::size_t(at)].slot == slot) {
        Entry& e = h.e[std::size_t(at)];
        (hit ? e.hits : e.free) += 1;
    } else {
        for (int j = h.n; j > at; --j) h.e[std::size_t(j)] = h.e[std::size_t(j - 1)];
        h.e[std::size_t(at)] = Entry{slot, hit ? 1u : 0u, hit ? 0u : 1u};
        ++h.n;
        merge_closest(h, max_entries);
    }
    assign(h);
}

std::uint32_t VoxelHistory::hit_span() const { return get(&bytes_[4], 2); }

SlotHistogram VoxelHistory::hit_histogram() const {
    const Entries h = entries();
    SlotHistogram out;
    for (int k = 0; k < h.n; ++k)
        if (h.e[std::size_t(k)].hits > 0)
            out.push_back({h.e[std::size_t(k)].slot, std::uint16_t(h.e[std::size_t(k)].hits)});
    return out;
}

void VoxelHistory::histograms(SlotHistogram* hits, SlotHistogram* views) const {
    hits->clear();
    views->clear();
    const Entries h = entries();
    for (int k = 0; k < h.n; ++k) {
        const Entry& e = h.e[std::size_t(k)];
        if (e.hits > 0) hits->push_back({e.slot, std::uint16_t(e.hits)});
        // Counts are at most kMaxCount each: their sum fits a histogram's count.
        views->push_back({e.slot, std::uint16_t(e.hits + e.free)});
    }
}

SlotHistogram VoxelHistory::free_histogram() const {
    const Entries h = entries();
    SlotHistogram out;
    for (int k = 0; k < h.n; ++k)
        if (h.e[std::size_t(k)].free > 0)
            out.push_back({h.e[std::size_t(k)].slot, std::uint16_t(h.e[std::size_t(k)].free)});
    return out;
}

}  // namespace ltm::maintenance
