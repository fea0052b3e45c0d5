#include "maintenance/core/region_columns.hpp"

#include <cstdlib>

#include "common/core/column_block.hpp"

namespace ltm::maintenance {
namespace {

enum Column : std::size_t {
    kKey,
    kCount,
    kSum,
    kSumSq,
    kCreated,
    kLast,
    kFlags,
    kFirstHit,
    kSpan,
    kEntries,
    kSlot,
    kHits,
    kFree,
    kColumns
};
const std::vector<std::size_t> kWidths = {8, 1, 2, 2, 4, 4, 1, 4, 2, 1, 4, 2, 2};

// The bytes the columns of n voxels with e entries in all take, unpacked.
std::uint64_t column_bytes(const std::vector<std::uint64_t>& counts) {
    std::uint64_t n = 0;
    for (std::size_t c = 0; c < kColumns; ++c) n += counts[c] * kWidths[c];
    return n;
}

}  // namespace

void write_region_columns(common::ByteWriter& w, const ObservationMap& map) {
    common::ColumnBlock b(kWidths);
    std::uint64_t key = 0;
    std::uint32_t created = 0, first_hit = 0;
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        const ObservedVoxel& v = map.voxel(i);
        b.put(kKey, std::uint64_t(v.key() - key));
        key = v.key();
        b.put(kCount, v.points.count);
        for (std::int16_t x : v.points.sum) b.put(kSum, x);
        for (std::int16_t x : v.points.sum_sq) b.put(kSumSq, x);
        b.put(kCreated, std::uint32_t(v.created_ticks - created));
        created = v.created_ticks;
        b.put(kLast, std::uint32_t(v.last_point_ticks - v.created_ticks));
        b.put(kFlags, v.flags);
        const VoxelHistory::Entries h = v.history.entries();
        b.put(kFirstHit, std::uint32_t(std::uint32_t(h.first_hit) - first_hit));
        first_hit = std::uint32_t(h.first_hit);
        b.put(kSpan, static_cast<std::uint16_t>(v.history.hit_span()));
        b.put(kEntries, static_cast<std::uint8_t>(h.n));
        for (int k = 0; k < h.n; ++k) {
            const VoxelHistory::Entry& e = h.e[std::size_t(k)];
            b.put(kSlot, std::int32_t(e.slot - h.first_hit));
            b.put(kHits, static_cast<std::uint16_t>(e.hits));
            b.put(kFree, static_cast<std::uint16_t>(e.free));
        }
    }
    const std::vector<std::uint64_t> counts = b.counts();
    const std::vector<std::uint8_t> planes = b.planes();
    for (std::uint64_t c : counts) w.value(c);
    w.value(std::uint64_t(planes.size()));
    const std::vector<std::uint8_t> frame =
        common::zstd_compress(planes.data(), planes.size(), common::kColumnZstdLevel);
    w.raw(frame.data(), frame.size());
}

void read_region_columns(common::ByteReader& s, std::uint32_t voxels, ObservationMap& map) {
    const std::uint64_t at = s.offset();
    std::vector<std::uint64_t> counts(kColumns);
    for (std::uint64_t& c : counts) s.value(c, "columns");
    const auto raw = s.get<std::uint64_t>("columns");
    // A voxel holds one value of each of its columns, at most kCapacity entries.
    const std::uint64_t n = voxels;
    const std::uint64_t entries = counts[kSlot];
    s.check(counts[kKey] == n && counts[kCount] == n && counts[kSum] == 3 * n &&
                counts[kSumSq] == 6 * n && counts[kCreated] == n && counts[kLast] == n &&
                counts[kFlags] == n && counts[kFirstHit] == n && counts[kSpan] == n &&
                counts[kEntries] == n && entries <= n * VoxelHistory::kCapacity &&
                counts[kHits] == entries && counts[kFree] == entries && raw == column_bytes(counts),
            "columns", at, "column counts that do not fit the voxel count");
    std::vector<std::uint8_t> frame(std::size_t(s.remaining()));
    s.raw(frame.data(), frame.size(), "columns");
    common::ColumnReader r(common::zstd_decompress(frame.data(), frame.size(), std::size_t(raw),
                                                   s.source(), "columns"),
                           kWidths, counts, s.source());
    const auto fail = [&](const char* field, const std::string& problem) {
        throw common::FormatError(s.source(), field, at, problem);
    };
    map.reserve(map.size() + voxels);
    std::uint64_t key = 0;
    std::uint32_t created = 0, first_hit = 0;
    for (std::uint32_t i = 0; i < voxels; ++i) {
        ObservedVoxel v;
        key += r.get<std::uint64_t>(kKey, "key");
        v.set_key(key);
        v.points.count = r.get<std::uint8_t>(kCount, "points");
        if (v.points.count > PointSums::kMaxPoints) fail("points", "more than 64 points");
        for (std::int16_t& x : v.points.sum) x = r.get<std::int16_t>(kSum, "sum");
        for (std::int16_t& x : v.points.sum_sq) x = r.get<std::int16_t>(kSumSq, "sum_sq");
        created += r.get<std::uint32_t>(kCreated, "created");
        v.created_ticks = created;
        const auto last = r.get<std::uint32_t>(kLast, "last_point");
        if (last > ~v.created_ticks) fail("last_point", "beyond the tick range");
        v.last_point_ticks = v.created_ticks + last;
        v.flags = r.get<std::uint8_t>(kFlags, "flags");
        VoxelHistory::Entries h;
        first_hit += r.get<std::uint32_t>(kFirstHit, "history");
        h.first_hit = std::int32_t(first_hit);
        const auto span = r.get<std::uint16_t>(kSpan, "history");
        h.last_hit = std::int32_t(std::int64_t(h.first_hit) + span);
        const auto n_entries = r.get<std::uint8_t>(kEntries, "history");
        if (n_entries > VoxelHistory::kCapacity)
            fail("history", std::to_string(n_entries) + " entries, more than " +
                                std::to_string(VoxelHistory::kCapacity));
        h.n = n_entries;
        for (int k = 0; k < h.n; ++k) {
            VoxelHistory::Entry& e = h.e[std::size_t(k)];
            const auto offset = r.get<std::int32_t>(kSlot, "history");
            if (std::abs(std::int64_t(offset)) > VoxelHistory::kMaxOffset)
                fail("history", "an entry more than 2^23 slots from the first hit");
            e.slot = std::int32_t(std::int64_t(h.first_hit) + offset);
            e.hits = r.get<std::uint16_t>(kHits, "history");
            e.free = r.get<std::uint16_t>(kFree, "history");
            if (e.hits + e.free == 0 || e.hits > VoxelHistory::kMaxCount ||
                e.free > VoxelHistory::kMaxCount)
                fail("history", "an entry with no views or more than 4095");
            if (k > 0 && e.slot <= h.e[std::size_t(k - 1)].slot)
                fail("history", "entries not in increasing order");
        }
        v.history.assign(h);
        if (!map.restore(v)) fail("key", "a repeated voxel");
    }
    r.expect_end("columns");
}

}  // namespace ltm::maintenance
