#include "maintenance/core/change_record.hpp"

#include <cstring>

#include "common/core/byte_io.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"

namespace ltm::maintenance {
namespace {

using common::ByteReader;
using common::ByteWriter;

constexpr char kMagic[8] = {'L', 'T', 'M', '-', 'C', 'H', 'N', 'G'};
// The smallest change section: length, body without voxels (93 bytes), CRC.
constexpr std::uint64_t kMinChangeBytes = 4 + 93 + 4;

// The record is described once, for both directions (as map/core/map_codec.cpp): ByteWriter
// runs it over a const ChangeSet and writes, ByteReader over a fresh one, reads and checks.

template <class IO, class T>
void count_as_u64(IO& io, T& v, const char* field) {
    std::uint64_t s = static_cast<std::uint64_t>(v);
    io.value(s, field);
    if constexpr (IO::kReading) v = static_cast<T>(s);
}

template <class IO, class V>
void vec(IO& io, V& v, int n, const char* field) {
    for (int i = 0; i < n; ++i) io.value(v[i], field);
}

template <class IO, class C>
void segment_change(IO& io, C& c) {
    io.value(c.id, "id");
    const std::uint64_t at_reason = io.offset();
    std::uint8_t reason = static_cast<std::uint8_t>(c.reason);
    io.value(reason, "reason");
    io.check(reason <= static_cast<std::uint8_t>(ChangeReason::kNew), "reason", at_reason,
             [&] { return "unknown reason " + std::to_string(reason); });
    if constexpr (IO::kReading) c.reason = static_cast<ChangeReason>(reason);
    vec(io, c.region, 2, "region");
    vec(io, c.centroid, 3, "centroid");
    vec(io, c.bbox_min, 3, "bbox_min");
    const std::uint64_t at_max = io.offset();
    vec(io, c.bbox_max, 3, "bbox_max");
    io.check((c.bbox_min.array() <= c.bbox_max.array()).all(), "bbox_max", at_max,
             "below bbox_min");
    io.value(c.first_seen, "first_seen");
    const std::uint64_t at_last = io.offset();
    io.value(c.last_seen, "last_seen");
    io.check(c.last_seen >= c.first_seen, "last_seen", at_last, "before first_seen");
    io.value(c.score, "score");
    io.value(c.judged, "judged");
    const std::uint64_t at_count = io.offset();
    std::uint32_t n = static_cast<std::uint32_t>(c.voxels.size());
    io.value(n, "voxel count");
    if constexpr (IO::kReading) {
        io.check(std::uint64_t(n) * 12 <= io.remaining(), "voxel count", at_count, [&] {
            return std::to_string(n) + " voxels do not fit in the " +
                   std::to_string(io.remaining()) + " bytes left";
        });
        c.voxels.resize(n);
    }
    for (std::uint32_t i = 0; i < n; ++i) vec(io, c.voxels[i], 3, "voxels");
}

template <class IO, class S>
void change_record(IO& io, S& s) {
    char magic[8];
    std::memcpy(magic, kMagic, 8);
    io.raw(magic, 8, "magic");
    io.check(std::memcmp(magic, kMagic, 8) == 0, "magic", 0, "not an ltm change record");
    const std::uint64_t at_version = io.offset();
    std::uint32_t version = kChangeRecordVersion;
    io.value(version, "format version");
    io.check(version == kChangeRecordVersion, "format version", at_version, [&] {
        return "format " + std::to_string(version) + " is not supported (this build reads " +
               std::to_string(kChangeRecordVersion) + ")";
    });
    std::uint64_t n = s.changes.size();
    io.section("header", [&](auto& h) {
        h.item("header");
        h.value(s.session, "session");
        h.value(s.map_time, "map_time");
        const std::uint64_t at_voxel = h.offset();
        h.value(s.voxel_size, "voxel_size");
        h.check(s.voxel_size > 0.0f, "voxel_size", at_voxel, "must be positive");
        count_as_u64(h, s.voxels_before, "voxels_before");
        count_as_u64(h, s.voxels_removed, "voxels_removed");
        count_as_u64(h, s.voxels_judged, "voxels_judged");
        count_as_u64(h, s.segments, "segments");
        count_as_u64(h, s.ground_voxels, "ground_voxels");
        h.value(s.time_ms, "time_ms");
        const std::uint64_t at_n = h.offset();
        h.value(n, "change count");
        if constexpr (IO::kReading) {
            h.check(n <= io.remaining() / kMinChangeBytes, "change count", at_n, [&] {
                return std::to_string(n) + " changes do not fit in the " +
                       std::to_string(io.remaining()) + " bytes left";
            });
        }
    });
    if constexpr (IO::kReading) s.changes.resize(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        io.section("changes[" + std::to_string(i) + "]", [&](auto& c) {
            c.item("changes", i);
            segment_change(c, s.changes[i]);
        });
    }
    io.expect_end("change record");
}

}  // namespace

std::string encode_change_record(const ChangeSet& changes) {
    ByteWriter w;
    change_record(w, changes);
    return std::string(w.bytes().begin(), w.bytes().end());
}

ChangeSet decode_change_record(const std::string& bytes, const std::string& source) {
    ByteReader r(source, bytes.data(), bytes.size());
    ChangeSet s;
    change_record(r, s);
    return s;
}

void write_change_record(const std::string& path, const ChangeSet& changes) {
    common::write_file_atomic(path, encode_change_record(changes));
}

ChangeSet read_change_record(const std::string& path) {
    return decode_change_record(common::read_file(path, path), path);
}

}  // namespace ltm::maintenance
