#include "link/core/local_map_columns.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

#include "link/core/cdr_cursor.hpp"

namespace ltm::link {
namespace {

// The fixed-size fields of one Voxel_ (and its VoxelLife_), in CDR order, with their sizes.
constexpr std::size_t kFields = 17;
constexpr std::size_t kFieldSize[kFields] = {4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 8, 8, 4, 4, 4};
constexpr std::size_t kDeltaFields = 3;  // ix, iy, iz: stored as differences
constexpr std::size_t kSeenCount = 16;   // the field holding the length of `seen`

std::size_t fixed_bytes() {
    std::size_t n = 0;
    for (std::size_t s : kFieldSize) n += s;
    return n;
}

struct Parsed {
    std::size_t prefix = 0;  // bytes before the voxel count
    std::uint32_t voxels = 0;
    std::vector<std::vector<std::uint8_t>> columns;  // one per field, voxels * size bytes
    std::vector<std::uint8_t> seen;                  // every voxel's `seen`, 2 bytes each
    std::size_t suffix = 0;                          // where the bytes after the voxels start
};

bool skip_header(CdrReader& r) {
    std::int32_t sec;
    std::uint32_t nsec;
    return r.read(sec) && r.read(nsec) && r.skip_string();
}

bool parse(const std::vector<std::uint8_t>& cdr, Parsed& p) {
    if (!is_cdr_le(cdr)) return false;
    CdrReader r(cdr.data(), cdr.size());
    std::uint64_t u64;
    std::uint32_t u32;
    std::uint8_t u8;
    double d;
    float f;
    std::size_t offset;
    if (!skip_header(r) || !r.read(u64) || !r.read(u32) || !r.read(u8) || !r.read(u32))
        return false;
    for (int i = 0; i < 7 + 7 + 3 + 3; ++i)  // anchor, grid_in_anchor, bbox_min, bbox_max
        if (!r.read(d)) return false;
    if (!r.read(f) || !r.sequence(8, u32, offset) || !r.align(4)) return false;
    p.prefix = r.pos();
    if (!r.read(p.voxels)) return false;
    // Each voxel takes at least its fixed fields: a count beyond the data is not a LocalMap_.
    if (p.voxels > (cdr.size() - r.pos()) / fixed_bytes()) return false;
    p.columns.assign(kFields, {});
    for (std::size_t k = 0; k < kFields; ++k) p.columns[k].reserve(p.voxels * kFieldSize[k]);
    std::uint32_t previous[kDeltaFields] = {0, 0, 0};
    for (std::uint32_t v = 0; v < p.voxels; ++v) {
        for (std::size_t k = 0; k < kFields; ++k) {
            std::uint8_t bytes[8];
            if (kFieldSize[k] == 8) {
                if (!r.read(u64)) return false;
                std::memcpy(bytes, &u64, 8);
            } else {
                if (!r.read(u32)) return false;
                if (k < kDeltaFields) {
                    const std::uint32_t value = u32;
                    u32 -= previous[k];
                    previous[k] = value;
                }
                std::memcpy(bytes, &u32, 4);
            }
            p.columns[k].insert(p.columns[k].end(), bytes, bytes + kFieldSize[k]);
        }
        std::uint32_t count;
        std::memcpy(&count, p.columns[kSeenCount].data() + 4 * v, 4);
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
    const std::uint32_t prefix = u32("the header");
    if (prefix < kCdrHeader || prefix > in.size() - at) malformed("bad header length");
    std::vector<std::uint8_t> out(in.begin() + at, in.begin() + at + prefix);
    at += prefix;
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
    CdrWriter w(out);
    w.write(voxels);
    std::uint32_t previous[kDeltaFields] = {0, 0, 0};
    std::size_t seen_at = 0;
    for (std::uint32_t v = 0; v < voxels; ++v) {
        for (std::size_t k = 0; k < kFields; ++k) {
            const std::uint8_t* b = columns[k].data() + v * kFieldSize[k];
            if (kFieldSize[k] == 8) {
                std::uint64_t x;
                std::memcpy(&x, b, 8);
                w.write(x);
            } else {
                std::uint32_t x;
                std::memcpy(&x, b, 4);
                if (k < kDeltaFields) x = previous[k] += x;
                w.write(x);
            }
        }
        std::uint32_t count;
        std::memcpy(&count, columns[kSeenCount].data() + 4 * v, 4);
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
