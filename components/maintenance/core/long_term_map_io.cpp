// The maintained map's file: "LTMMAINT", format version, then CRC-checked sections: the header
// (lattice, clock, sessions) and one section a region (its voxels with their histories).
#include <cmath>
#include <cstring>

#include "common/core/byte_io.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "maintenance/core/long_term_map.hpp"

namespace ltm::maintenance {

namespace {

constexpr char kMagic[8] = {'L', 'T', 'M', 'M', 'A', 'I', 'N', 'T'};
constexpr std::uint32_t kVersion = 1;

template <class IO>
void histogram_io(IO& io, SlotHistogram& h, const char* name, std::size_t max_slots) {
    auto n = static_cast<std::uint16_t>(h.size());
    const std::uint64_t at = io.offset();
    io.value(n, name);
    io.check(n <= max_slots, name, at, [&] {
        return std::to_string(n) + " slots, more than max_slots " + std::to_string(max_slots);
    });
    if constexpr (IO::kReading) h.resize(n);
    std::int32_t previous = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint64_t at_slot = io.offset();
        io.value(h[k].slot, name);
        io.value(h[k].count, name);
        io.check(k == 0 || h[k].slot > previous, name, at_slot, "slots not in increasing order");
        previous = h[k].slot;
    }
}

template <class IO>
void voxel_io(IO& io, registration::VoxelKey& key, ObservedVoxel& v, std::size_t max_slots) {
    io.value(key, "key");
    io.value(v.sums.weight, "weight");
    for (int k = 0; k < 3; ++k) io.value(v.sums.sum[k], "sum");
    for (int k = 0; k < 6; ++k) io.value(v.sums.sum_sq[k], "sum_sq");
    io.value(v.created, "created");
    io.value(v.last_point, "last_point");
    io.value(v.session, "session");
    io.value(v.flags, "flags");
    histogram_io(io, v.hits, "hits", max_slots);
    histogram_io(io, v.free, "free", max_slots);
}

}  // namespace

void LongTermMap::save(const std::string& path) const {
    common::ByteWriter w;
    w.raw(kMagic, sizeof kMagic);
    w.value(kVersion);
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
        s.value(static_cast<std::uint32_t>(regions_.size()));
    });
    for (const auto& entry : regions_) {
        const std::pair<int, int> key = entry.first;
        const ObservationMap& map = *entry.second;
        w.section("region", [&](auto& s) {
            s.value(std::int32_t(key.first));
            s.value(std::int32_t(key.second));
            s.value(static_cast<std::uint32_t>(map.size()));
            for (std::uint32_t i = 0; i < map.size(); ++i) {
                registration::VoxelKey k = map.key(i);
                ObservedVoxel v = map.voxel(i);
                voxel_io(s, k, v, std::size_t(config_.max_slots));
            }
        });
    }
    common::write_file_atomic(path, w.bytes().data(), w.bytes().size());
}

LongTermMap LongTermMap::load(const std::string& path, const MaintenanceConfig& config) {
    LongTermMap m(config);
    const std::string bytes = common::read_file(path, path);
    common::ByteReader r(path, bytes.data(), bytes.size());
    char magic[sizeof kMagic];
    r.raw(magic, sizeof magic, "magic");
    if (std::memcmp(magic, kMagic, sizeof kMagic) != 0)
        r.fail_at("magic", 0, "not a maintained map (no LTMMAINT signature)");
    const std::uint64_t at_version = r.offset();
    const auto version = r.get<std::uint32_t>("version");
    r.check(version == kVersion, "version", at_version, [&] {
        return "format version " + std::to_string(version) +
               " is not supported (this build reads " + std::to_string(kVersion) + ")";
    });
    std::uint32_t regions = 0;
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
        s.check(std::uint64_t(n) * 4 <= s.remaining(), "sessions", at, "more than the file holds");
        m.sessions_.resize(n);
        for (std::uint32_t& id : m.sessions_) s.value(id, "sessions");
        s.value(regions, "regions");
    });
    for (std::uint32_t k = 0; k < regions; ++k) {
        r.section("region", [&](common::ByteReader& s) {
            const auto x = s.get<std::int32_t>("region.x");
            const auto y = s.get<std::int32_t>("region.y");
            const std::uint64_t at = s.offset();
            const auto n = s.get<std::uint32_t>("voxels");
            constexpr std::uint64_t kMinVoxelBytes = 73;  // a voxel with empty histories
            s.check(std::uint64_t(n) * kMinVoxelBytes <= s.remaining(), "voxels", at,
                    "more voxels than the section holds");
            ObservationMap& map = m.region({x, y});
            for (std::uint32_t i = 0; i < n; ++i) {
                s.item("voxels", i);
                const std::uint64_t at_voxel = s.offset();
                registration::VoxelKey key = 0;
                ObservedVoxel v;
                voxel_io(s, key, v, std::size_t(config.max_slots));
                s.check(map.restore(key, std::move(v)), "key", at_voxel, "a repeated voxel");
            }
        });
    }
    r.expect_end("the map");
    m.in_session_ = false;
    return m;
}

}  // namespace ltm::maintenance
