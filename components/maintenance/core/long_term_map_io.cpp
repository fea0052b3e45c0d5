// The maintained map's file: "LTMMAINT", format version, then CRC-checked sections: the header
// (lattice, clock, sessions) and one section a region (its voxels with their histories).
// Version 3 stores a region's voxels as compressed columns (region_columns.hpp, lossless);
// version 2 files (the compact voxel as it is in memory, 43 bytes + 8 a history entry) are read as
// they are, version 1 files (float sums, separate histograms) read and converted.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "common/core/byte_io.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "common/core/streamed_file.hpp"
#include "maintenance/core/long_term_map.hpp"
#include "maintenance/core/region_columns.hpp"
#include "maintenance/core/region_io.hpp"

namespace ltm::maintenance {

namespace {

constexpr char kMagic[8] = {'L', 'T', 'M', 'M', 'A', 'I', 'N', 'T'};
// 3: version 2's voxels as compressed columns (issue 26: about a third of the bytes).
// 2: the compact voxel (fixed-point point sums, ticks, one view history of at most 6 entries).
// 1: float sums, double times, separate hit and free histograms; still read, converted.
// (kMaintainedMapVersion and kMaintainedMapVersion1, region_io.hpp)

template <class IO>
void history_io(IO& io, VoxelHistory& history) {
    VoxelHistory::Entries h;
    if constexpr (!IO::kReading) h = history.entries();
    auto span = static_cast<std::uint16_t>(history.hit_span());
    io.value(h.first_hit, "history");
    io.value(span, "history");
    h.last_hit = std::int32_t(std::int64_t(h.first_hit) + span);
    auto n = static_cast<std::uint8_t>(h.n);
    const std::uint64_t at = io.offset();
    io.value(n, "history");
    io.check(n <= VoxelHistory::kCapacity, "history", at, [&] {
        return std::to_string(n) + " entries, more than " + std::to_string(VoxelHistory::kCapacity);
    });
    h.n = n;
    for (int k = 0; k < h.n; ++k) {
        VoxelHistory::Entry& e = h.e[std::size_t(k)];
        auto hits = static_cast<std::uint16_t>(e.hits), free = static_cast<std::uint16_t>(e.free);
        const std::uint64_t at_entry = io.offset();
        io.value(e.slot, "history");
        io.value(hits, "history");
        io.value(free, "history");
        e.hits = hits;
        e.free = free;
        io.check(
            hits + free > 0 && hits <= VoxelHistory::kMaxCount && free <= VoxelHistory::kMaxCount,
            "history", at_entry, "an entry with no views or more than 4095");
        io.check(k == 0 || e.slot > h.e[std::size_t(k - 1)].slot, "history", at_entry,
                 "entries not in increasing order");
        io.check(std::abs(std::int64_t(e.slot) - h.first_hit) <= VoxelHistory::kMaxOffset,
                 "history", at_entry, "an entry more than 2^23 slots from the first hit");
    }
    if constexpr (IO::kReading) history.assign(h);
}

template <class IO>
void voxel_io(IO& io, ObservedVoxel& v) {
    io.value(v.key_lo, "key");
    io.value(v.key_hi, "key");
    const std::uint64_t at = io.offset();
    io.value(v.points.count, "points");
    io.check(v.points.count <= PointSums::kMaxPoints, "points", at, "more than 64 points");
    for (std::int16_t& x : v.points.sum) io.value(x, "sum");
    for (std::int16_t& x : v.points.sum_sq) io.value(x, "sum_sq");
    io.value(v.created_ticks, "created");
    const std::uint64_t at_last = io.offset();
    io.value(v.last_point_ticks, "last_point");
    io.check(v.last_point_ticks >= v.created_ticks, "last_point", at_last, "before created");
    io.value(v.flags, "flags");
    history_io(io, v.history);
}

// A voxel of a version-1 file, converted: the sums to fixed point, the times to ticks, the hit and
// free histograms to one history (merged to its capacity as views would have been).
void read_voxel_v1(common::ByteReader& io, float voxel_size, ObservedVoxel& v) {
    registration::VoxelKey key = 0;
    io.value(key, "key");
    v.set_key(key);
    registration::VoxelSums s;
    io.value(s.weight, "weight");
    for (int k = 0; k < 3; ++k) io.value(s.sum[k], "sum");
    for (int k = 0; k < 6; ++k) io.value(s.sum_sq[k], "sum_sq");
    const float unit = voxel_size / PointSums::kUnitsPerVoxel;
    const auto fixed = [](double x) {
        return std::int16_t(std::clamp(std::lround(std::isfinite(x) ? x : 0.0), -32767l, 32767l));
    };
    v.points.count =
        std::uint8_t(std::clamp(std::lround(s.weight), 0l, long(PointSums::kMaxPoints)));
    for (int k = 0; k < 3; ++k) v.points.sum[std::size_t(k)] = fixed(s.sum[k] / unit);
    for (int k = 0; k < 6; ++k)
        v.points.sum_sq[std::size_t(k)] =
            fixed(s.sum_sq[k] / (PointSums::kSquareUnit * unit * unit));
    const double created = io.get<double>("created"), last = io.get<double>("last_point");
    v.created_ticks = to_ticks(created);
    v.last_point_ticks = std::max(v.created_ticks, to_ticks(last));
    io.get<std::uint32_t>("session");
    io.value(v.flags, "flags");
    std::map<std::int32_t, VoxelHistory::Entry> by_slot;
    for (const bool hit : {true, false}) {
        const char* name = hit ? "hits" : "free";
        const std::uint64_t at = io.offset();
        const auto n = io.get<std::uint16_t>(name);
        io.check(std::uint64_t(n) * 6 <= io.remaining(), name, at,
                 "more slots than the file holds");
        for (std::size_t k = 0; k < n; ++k) {
            const auto slot = io.get<std::int32_t>(name);
            const auto count = io.get<std::uint16_t>(name);
            VoxelHistory::Entry& e = by_slot[slot];
            e.slot = slot;
            (hit ? e.hits : e.free) = count;
        }
    }
    VoxelHistory::Entries h;
    bool hit = false;
    for (const auto& [slot, e] : by_slot) {
        if (e.hits + e.free == 0) continue;
        if (e.hits > 0) {
            h.first_hit = hit ? h.first_hit : slot;
            h.last_hit = slot;
            hit = true;
        }
        h.e[std::size_t(h.n++)] = e;
        merge_closest(h, VoxelHistory::kCapacity);
    }
    v.history.assign(h);
}

}  // namespace

void write_region_section(common::ByteWriter& w, const std::pair<int, int>& key,
                          const ObservationMap& map) {
    w.section("region", [&](auto& s) {
        s.value(std::int32_t(key.first));
        s.value(std::int32_t(key.second));
        s.value(static_cast<std::uint32_t>(map.size()));
        write_region_columns(s, map);
    });
}

namespace detail {

std::pair<int, int> read_region_key(common::ByteReader& s) {
    const auto x = s.get<std::int32_t>("region.x");
    const auto y = s.get<std::int32_t>("region.y");
    return {x, y};
}

void read_region_voxels(common::ByteReader& s, std::uint32_t version, float voxel_size,
                        ObservationMap& map) {
    const std::uint64_t at = s.offset();
    const auto n = s.get<std::uint32_t>("voxels");
    if (version == kMaintainedMapVersion) {
        read_region_columns(s, n, map);
        return;
    }
    // A voxel with an empty history: 43 bytes (version 1: 73).
    const std::uint64_t min_voxel_bytes = version == kMaintainedMapVersion1 ? 73 : 43;
    s.check(std::uint64_t(n) * min_voxel_bytes <= s.remaining(), "voxels", at,
            "more voxels than the section holds");
    map.reserve(map.size() + n);
    for (std::uint32_t i = 0; i < n; ++i) {
        s.item("voxels", i);
        const std::uint64_t at_voxel = s.offset();
        ObservedVoxel v;
        if (version == kMaintainedMapVersion1) {
            read_voxel_v1(s, voxel_size, v);
        } else {
            voxel_io(s, v);
        }
        s.check(map.restore(v), "key", at_voxel, "a repeated voxel");
    }
}

}  // namespace detail

// Written a region at a time to PATH.tmp (the paged-out regions' sections copied from their
// files), then renamed: the file is never whole in memory.
void LongTermMap::save(const std::string& path) const {
    common::AtomicFileWriter out(path);
    {
        common::ByteWriter w;
        w.raw(kMagic, sizeof kMagic);
        w.value(kMaintainedMapVersion);
        w.section("header", [&](auto& s) {
            s.value(config_.voxel_size);
            s.value(config_.region_size);
            s.value(config_.slot);
            s.value(session_);
            s.value(session_offset_);
            s.value(now_);
            s.value(next_change_);
            s.value(static_cast<std::uint32_t>(sessions_.size()));
            for (std::uint32_t id : sessions_) s.value(id);
            const std::size_t paged = pager_ ? pager_->regions().size() : 0;
            s.value(static_cast<std::uint32_t>(regions_.size() + paged));
        });
        out.append(w.bytes());
    }
    std::set<RegionKey> keys;
    for (const auto& entry : regions_) keys.insert(entry.first);
    if (pager_)
        for (const auto& entry : pager_->regions()) keys.insert(entry.first);
    for (const RegionKey& key : keys) {  // in key order, as before paging
        const auto it = regions_.find(key);
        if (it != regions_.end()) {
            common::ByteWriter w;
            write_region_section(w, key, *it->second);
            out.append(w.bytes());
        } else {
            out.append(pager_->section(key));
        }
    }
    out.commit();
}

// Read a section at a time; with paging (set_paging before, or `paging` here), every region goes
// to disk as it is read and comes back when the robot approaches it.
LongTermMap LongTermMap::load(const std::string& path, const MaintenanceConfig& config,
                              const PagingConfig& paging) {
    LongTermMap m(config);
    m.set_paging(paging);
    common::SectionFileReader file(path, path);
    std::uint32_t version = 0;
    {
        const std::vector<std::uint8_t> head = file.bytes(sizeof kMagic + 4, "magic");
        common::ByteReader r(path, head.data(), head.size());
        char magic[sizeof kMagic];
        r.raw(magic, sizeof magic, "magic");
        if (std::memcmp(magic, kMagic, sizeof kMagic) != 0)
            r.fail_at("magic", 0, "not a maintained map (no LTMMAINT signature)");
        const std::uint64_t at_version = r.offset();
        version = r.get<std::uint32_t>("version");
        r.check(version == kMaintainedMapVersion || version == kMaintainedMapVersion2 ||
                    version == kMaintainedMapVersion1,
                "version", at_version, [&] {
                    return "format version " + std::to_string(version) +
                           " is not supported (this build reads 1 to " +
                           std::to_string(kMaintainedMapVersion) + ")";
                });
    }
    std::uint32_t regions = 0;
    file.next_section("header");
    {
        common::ByteReader r = file.reader();
        r.section("header", [&](common::ByteReader& s) {
            const auto same = [&](const char* field, double expected) {
                const std::uint64_t at = s.offset();
                const auto v = s.get<double>(field);
                s.check(std::abs(v - expected) < 1e-9, field, at, [&] {
                    return "the map was made with " + std::string(field) + " " + std::to_string(v) +
                           ", the configuration says " + std::to_string(expected);
                });
            };
            same("voxel_size", config.voxel_size);
            same("region_size", config.region_size);
            same("slot", config.slot);
            s.value(m.session_, "session");
            s.value(m.session_offset_, "session_offset");
            s.value(m.now_, "now");
            s.value(m.next_change_, "next_change");
            const std::uint64_t at = s.offset();
            const auto n = s.get<std::uint32_t>("sessions");
            s.check(std::uint64_t(n) * 4 <= s.remaining(), "sessions", at,
                    "more than the file holds");
            m.sessions_.resize(n);
            for (std::uint32_t& id : m.sessions_) s.value(id, "sessions");
            s.value(regions, "regions");
        });
    }
    for (std::uint32_t k = 0; k < regions; ++k) {
        const std::vector<std::uint8_t>& bytes = file.next_section("region");
        common::ByteReader r = file.reader();
        RegionKey key;
        read_region_section(
            r, version, float(config.voxel_size), [&](const RegionKey& read) -> ObservationMap& {
                key = read;
                r.check(!m.pager_ || !m.pager_->holds(read), "region", 0, "a repeated region");
                return m.region({read.first, read.second});
            });
        if (m.pager_) {  // checked above; on disk until the robot comes near
            const ObservationMap& map = *m.regions_.at(key);
            if (version == kMaintainedMapVersion) {
                m.pager_->page_out_section(key, bytes, map.size());
            } else {
                m.pager_->page_out(key, map);
            }
            m.regions_.erase(key);
        }
    }
    if (!file.at_end()) {
        throw common::FormatError(path, "the map", file.offset(), "unexpected bytes after the end");
    }
    m.in_session_ = false;
    return m;
}

}  // namespace ltm::maintenance
