#include "link/core/local_map_columns.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "common/core/cdr_cursor.hpp"

namespace ltm::link {
namespace {

// The fixed-size fields of one Voxel_ (and its VoxelLife_), in CDR order, with their sizes.
enum Field : std::size_t {
    kIx,
    kIy,
    kIz,
    kCx,
    kCy,
    kCz,
    kNx,
    kNy,
    kNz,
    kPointCount,
    kPlanarity,
    kStability,
    kCreated,
    kLastSeen,
    kObservations,
    kHealth,
    kSeenCount,
    kFields
};
constexpr std::size_t kFieldSize[kFields] = {4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 8, 8, 4, 4, 4};
constexpr std::uint64_t kIndexLimit = std::uint64_t{1} << 32;  // time columns: index or value

std::size_t fixed_bytes() {
    std::size_t n = 0;
    for (std::size_t s : kFieldSize) n += s;
    return n;
}

float as_float(std::uint64_t bits) {
    const auto b = static_cast<std::uint32_t>(bits);
    float f;
    std::memcpy(&f, &b, 4);
    return f;
}

std::uint32_t float_bits(float f) {
    std::uint32_t b;
    std::memcpy(&b, &f, 4);
    return b;
}

// What the map's header says about its voxels: the lattice's size and the scans' stamps.
struct Prefix {
    float voxel_size = 0;
    std::unordered_map<std::uint64_t, std::uint32_t> time_index;  // stamp bits -> first index
    std::vector<std::uint64_t> times;                             // observation_times' bits
};

// Everything of a LocalMap_ before its voxel count; false when it is not one.
bool parse_prefix(common::CdrReader& r, const std::uint8_t* data, Prefix& p) {
    std::int32_t sec;
    std::uint32_t u32, nsec, count;
    std::uint64_t u64;
    std::uint8_t u8;
    double d;
    std::size_t offset;
    if (!r.read(sec) || !r.read(nsec) || !r.skip_string() || !r.read(u64) || !r.read(u32) ||
        !r.read(u8) || !r.read(u32))
        return false;
    for (int i = 0; i < 7 + 7 + 3 + 3; ++i)  // anchor, grid_in_anchor, bbox_min, bbox_max
        if (!r.read(d)) return false;
    if (!r.read(p.voxel_size) || !r.sequence(8, count, offset) || !r.align(4)) return false;
    p.times.resize(count);
    if (count > 0) std::memcpy(p.times.data(), data + offset, 8 * std::size_t{count});
    for (std::uint32_t i = count; i-- > 0;) p.time_index[p.times[i]] = i;
    return true;
}

// Each field as stored in its column, given the voxel's fields before it (`raw`) and the previous
// voxel's (`previous`): indices as differences; centres as the difference of their bits to those
// of their cell's middle; the normal's z as the difference of its bits to sqrt(1 - x^2 - y^2)
// (computed in double, where the squares are exact: the same on every machine); stamps that are
// one of the map's observation times as 1 + that index, others moved above 2^32. Every step is an
// integer bijection, so each value comes back exactly, whatever it was.
struct Predictor {
    const Prefix& prefix;

    std::uint32_t centre_ref(std::uint64_t index) const {
        const auto i = static_cast<std::int32_t>(static_cast<std::uint32_t>(index));
        return float_bits((static_cast<float>(i) + 0.5f) * prefix.voxel_size);
    }
    static std::uint32_t normal_z_ref(std::uint64_t nx, std::uint64_t ny) {
        const double x = as_float(nx), y = as_float(ny);
        const double s = 1.0 - x * x - y * y;
        return float_bits(static_cast<float>(std::sqrt(s > 0 ? s : 0.0)));
    }

    // `raw` -> stored; false when a stamp cannot be told from an index (a NaN with the top bits).
    bool forward(std::size_t k, const std::uint64_t* raw, const std::uint64_t* previous,
                 std::uint64_t& out) const {
        const std::uint64_t v = raw[k];
        switch (k) {
            case kIx:
            case kIy:
            case kIz:
                out = static_cast<std::uint32_t>(v - previous[k]);
                return true;
            case kCx:
            case kCy:
            case kCz:
                out = static_cast<std::uint32_t>(v - centre_ref(raw[k - kCx]));
                return true;
            case kNz:
                out = static_cast<std::uint32_t>(v - normal_z_ref(raw[kNx], raw[kNy]));
                return true;
            case kCreated:
            case kLastSeen: {
                const auto it = prefix.time_index.find(v);
                if (it != prefix.time_index.end()) {
                    out = std::uint64_t{it->second} + 1;
                    return true;
                }
                out = v + kIndexLimit + 1;
                return out == 0 || out > kIndexLimit;
            }
            default:
                out = v;
                return true;
        }
    }

    // Stored -> raw; false when a stamp names an observation time the map does not have.
    bool inverse(std::size_t k, std::uint64_t stored, const std::uint64_t* raw,
                 const std::uint64_t* previous, std::uint64_t& out) const {
        switch (k) {
            case kIx:
            case kIy:
            case kIz:
                out = static_cast<std::uint32_t>(stored + previous[k]);
                return true;
            case kCx:
            case kCy:
            case kCz:
                out = static_cast<std::uint32_t>(stored + centre_ref(raw[k - kCx]));
                return true;
            case kNz:
                out = static_cast<std::uint32_t>(stored + normal_z_ref(raw[kNx], raw[kNy]));
                return true;
            case kCreated:
            case kLastSeen:
                if (stored >= 1 && stored <= kIndexLimit) {
                    if (stored > prefix.times.size()) return false;
                    out = prefix.times[stored - 1];
                } else {
                    out = stored - kIndexLimit - 1;
                }
                return true;
            default:
                out = stored;
                return true;
        }
    }
};

struct Parsed {
    std::size_t prefix = 0;  // bytes before the voxel count
    std::uint32_t voxels = 0;
    std::vector<std::vector<std::uint8_t>> columns;  // one per field, voxels * size bytes
    std::vector<std::uint8_t> seen;                  // every voxel's `seen`, 2 bytes each
    std::size_t suffix = 0;                          // where the bytes after the voxels start
};

bool parse(const std::vector<std::uint8_t>& cdr, Parsed& p) {
    if (!common::is_cdr_le(cdr)) return false;
    common::CdrReader r(cdr.data(), cdr.size());
    Prefix prefix;
    if (!parse_prefix(r, cdr.data(), prefix)) return false;
    p.prefix = r.pos();
    if (!r.read(p.voxels)) return false;
    // Each voxel takes at least its fixed fields: a count beyond the data is not a LocalMap_.
    if (p.voxels > (cdr.size() - r.pos()) / fixed_bytes()) return false;
    p.columns.assign(kFields, {});
    for (std::size_t k = 0; k < kFields; ++k) p.columns[k].reserve(p.voxels * kFieldSize[k]);
    const Predictor predict{prefix};
    std::uint64_t raw[kFields] = {}, previous[kFields] = {};
    for (std::uint32_t v = 0; v < p.voxels; ++v) {
        for (std::size_t k = 0; k < kFields; ++k) {
            std::uint32_t u32;
            if (kFieldSize[k] == 8) {
                if (!r.read(raw[k])) return false;
            } else {
                if (!r.read(u32)) return false;
                raw[k] = u32;
            }
            std::uint64_t stored;
            if (!predict.forward(k, raw, previous, stored)) return false;
            std::uint8_t bytes[8];
            std::memcpy(bytes, &stored, 8);  // little-endian: the low kFieldSize[k] bytes
            p.columns[k].insert(p.columns[k].end(), bytes, bytes + kFieldSize[k]);
        }
        std::memcpy(previous, raw, sizeof raw);
        const auto count = static_cast<std::uint32_t>(raw[kSeenCount]);
        if (count > 0) {
            if (!r.align(2) || count > (cdr.size() - r.pos()) / 2) return false;
            p.seen.insert(p.seen.end(), cdr.begin() + r.pos(), cdr.begin() + r.pos() + 2 * count);
            r.skip(2 * count);
        }
    }
    p.suffix = r.pos();
    return true;
}

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
    out.insert(out.end(), b, b + 4);
}

void append_shuffled(std::vector<std::uint8_t>& out, const std::vector<std::uint8_t>& column,
                     std::size_t stride) {
    const std::size_t at = out.size();
    out.resize(at + column.size());
    shuffle_bytes(column.data(), column.size() / stride, stride, out.data() + at);
}

[[noreturn]] void malformed(const std::string& what) {
    throw std::runtime_error("local map columns: " + what);
}

}  // namespace

void shuffle_bytes(const std::uint8_t* in, std::size_t n, std::size_t stride, std::uint8_t* out) {
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < stride; ++j) out[j * n + i] = in[i * stride + j];
}

void unshuffle_bytes(const std::uint8_t* in, std::size_t n, std::size_t stride, std::uint8_t* out) {
    for (std::size_t j = 0; j < stride; ++j)
        for (std::size_t i = 0; i < n; ++i) out[i * stride + j] = in[j * n + i];
}

std::optional<std::vector<std::uint8_t>> local_map_to_columns(
    const std::vector<std::uint8_t>& cdr) {
    Parsed p;
    if (!parse(cdr, p)) return std::nullopt;
    std::vector<std::uint8_t> out;
    out.reserve(cdr.size() + 16);
    put_u32(out, static_cast<std::uint32_t>(p.prefix));
    out.insert(out.end(), cdr.begin(), cdr.begin() + p.prefix);
    put_u32(out, p.voxels);
    for (std::size_t k = 0; k < kFields; ++k) append_shuffled(out, p.columns[k], kFieldSize[k]);
    append_shuffled(out, p.seen, 2);
    out.insert(out.end(), cdr.begin() + p.suffix, cdr.end());
    // Padding that is not zero (or a layout this parse does not reproduce) would not come back:
    // such a message is not rearranged.
    if (local_map_from_columns(out) != cdr) return std::nullopt;
    return out;
}

std::vector<std::uint8_t> local_map_from_columns(const std::vector<std::uint8_t>& in) {
    std::size_t at = 0;
    const auto u32 = [&](const char* what) {
        if (in.size() - at < 4) malformed(std::string("cut short in ") + what);
        std::uint32_t v;
        std::memcpy(&v, in.data() + at, 4);
        at += 4;
        return v;
    };
    const std::uint32_t prefix_size = u32("the header");
    if (prefix_size < common::kCdrHeader || prefix_size > in.size() - at)
        malformed("bad header length");
    std::vector<std::uint8_t> out(in.begin() + at, in.begin() + at + prefix_size);
    at += prefix_size;
    Prefix prefix;
    common::CdrReader header(out.data(), out.size());
    if (!parse_prefix(header, out.data(), prefix) || header.pos() != out.size())
        malformed("the header is not a local map's");
    const std::uint32_t voxels = u32("the voxel count");
    if (voxels > (in.size() - at) / fixed_bytes())
        malformed(std::to_string(voxels) + " voxels do not fit in " +
                  std::to_string(in.size() - at) + " bytes");
    std::vector<std::vector<std::uint8_t>> columns(kFields);
    for (std::size_t k = 0; k < kFields; ++k) {
        columns[k].resize(std::size_t{voxels} * kFieldSize[k]);
        unshuffle_bytes(in.data() + at, voxels, kFieldSize[k], columns[k].data());
        at += columns[k].size();
    }
    std::uint64_t seen_total = 0;
    for (std::uint32_t v = 0; v < voxels; ++v) {
        std::uint32_t count;
        std::memcpy(&count, columns[kSeenCount].data() + 4 * v, 4);
        seen_total += count;
    }
    if (seen_total > (in.size() - at) / 2)
        malformed(std::to_string(seen_total) + " seen indices do not fit");
    std::vector<std::uint8_t> seen(seen_total * 2);
    unshuffle_bytes(in.data() + at, seen_total, 2, seen.data());
    at += seen.size();

    out.reserve(in.size() + std::size_t{voxels} * 8);
    common::CdrWriter w(out);
    w.write(voxels);
    const Predictor predict{prefix};
    std::uint64_t raw[kFields] = {}, previous[kFields] = {};
    std::size_t seen_at = 0;
    for (std::uint32_t v = 0; v < voxels; ++v) {
        for (std::size_t k = 0; k < kFields; ++k) {
            std::uint64_t stored = 0;
            std::memcpy(&stored, columns[k].data() + v * kFieldSize[k], kFieldSize[k]);
            if (!predict.inverse(k, stored, raw, previous, raw[k]))
                malformed("voxel " + std::to_string(v) + " names observation time " +
                          std::to_string(stored - 1) + " of " +
                          std::to_string(prefix.times.size()));
            if (kFieldSize[k] == 8)
                w.write(raw[k]);
            else
                w.write(static_cast<std::uint32_t>(raw[k]));
        }
        std::memcpy(previous, raw, sizeof raw);
        const auto count = static_cast<std::uint32_t>(raw[kSeenCount]);
        if (count > 0) {
            w.align(2);
            w.bytes(seen.data() + seen_at, 2 * std::size_t{count});
            seen_at += 2 * std::size_t{count};
        }
    }
    w.bytes(in.data() + at, in.size() - at);
    return out;
}

}  // namespace ltm::link
