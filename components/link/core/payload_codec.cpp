#include "link/core/payload_codec.hpp"

#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "common/core/cdr_cursor.hpp"
#include "link/core/local_map_columns.hpp"

namespace ltm::link {
namespace {

const char* const kKeyframeType = "ltm_msgs::msg::dds_::Keyframe_";
const char* const kLocalMapType = "ltm_msgs::msg::dds_::LocalMap_";
constexpr std::size_t kMaxCdr = std::size_t{1} << 30;  // larger messages are not ltm's
constexpr std::size_t kPrefix = 5;                     // codec byte + CDR size

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error("payload: " + what); }

// Bytes [offset, offset + length) shuffled in elements of `stride` bytes; with `delta`, each
// 4-byte lane of an element first less the same lane of the element before (as uint32: points of
// a scan in scan order are near their predecessor, floats of one exponent near in their bits).
struct Range {
    std::uint32_t offset = 0, length = 0;
    std::uint16_t stride = 0;
    std::uint8_t delta = 0;
};
constexpr std::size_t kRangeBytes = 11;

void add_range(std::vector<Range>& ranges, std::size_t offset, std::size_t count,
               std::size_t stride, bool delta) {
    if (count >= 2 && stride >= 2 && stride <= 0xffff)
        ranges.push_back({static_cast<std::uint32_t>(offset),
                          static_cast<std::uint32_t>(count * stride),
                          static_cast<std::uint16_t>(stride),
                          static_cast<std::uint8_t>(delta && stride % 4 == 0)});
}

bool skip_header(common::CdrReader& r) {
    std::int32_t sec;
    std::uint32_t nsec;
    return r.read(sec) && r.read(nsec) && r.skip_string();
}

// The arrays of a Keyframe_ worth shuffling: the point cloud's data by point, the descriptors'
// float sequences by float. Whatever does not parse ends the list (still lossless: the ranges are
// only a permutation).
std::vector<Range> keyframe_ranges(const std::vector<std::uint8_t>& cdr) {
    std::vector<Range> ranges;
    if (!common::is_cdr_le(cdr)) return ranges;
    common::CdrReader r(cdr.data(), cdr.size());
    std::uint64_t u64;
    std::uint32_t u32, height, width, fields, point_step, count;
    std::uint8_t u8;
    std::uint16_t u16;
    double d;
    float f;
    std::size_t offset;
    if (!skip_header(r) || !r.read(u64) || !r.read(u64) || !r.read(u64) || !r.read(u32))
        return ranges;
    for (int i = 0; i < 14; ++i)  // pose, pose_in_anchor
        if (!r.read(d)) return ranges;
    if (!skip_header(r) || !r.read(height) || !r.read(width) || !r.read(fields)) return ranges;
    for (std::uint32_t i = 0; i < fields; ++i)  // PointField_: name, offset, datatype, count
        if (!r.skip_string() || !r.read(u32) || !r.read(u8) || !r.read(u32)) return ranges;
    if (!r.read(u8) || !r.read(point_step) || !r.read(u32) || !r.sequence(1, count, offset))
        return ranges;
    if (point_step > 0) add_range(ranges, offset, count / point_step, point_step, true);
    if (!r.read(u8)) return ranges;  // is_dense
    for (int d = 0; d < 2; ++d) {    // descriptor, localisation_descriptor
        if (!r.read(u8) || !r.read(u16) || !r.read(u16) || !r.read(f)) return ranges;
        for (int i = 0; i < 2; ++i) {  // values, spreads
            if (!r.sequence(4, count, offset)) return ranges;
            add_range(ranges, offset, count, 4, false);
        }
        if (!r.sequence(1, count, offset) || !r.read(f) || !r.read(f)) return ranges;  // occupied
    }
    return ranges;
}

// One zstd frame with its content size and a checksum of the content (damage on disk or in
// transit is an error, not other bytes).
std::vector<std::uint8_t> zstd_compress(const std::uint8_t* data, std::size_t size, int level) {
    std::vector<std::uint8_t> out(ZSTD_compressBound(size));
    ZSTD_CCtx* cctx = ZSTD_createCCtx();
    if (!cctx) fail("zstd: out of memory");
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_compressionLevel, level);
    ZSTD_CCtx_setParameter(cctx, ZSTD_c_checksumFlag, 1);
    const std::size_t n = ZSTD_compress2(cctx, out.data(), out.size(), data, size);
    ZSTD_freeCCtx(cctx);
    if (ZSTD_isError(n)) fail(std::string("zstd: ") + ZSTD_getErrorName(n));
    out.resize(n);
    return out;
}

// The zstd frame that must fill wire[at, end) and hold exactly `expected` bytes.
std::vector<std::uint8_t> zstd_decompress(const std::vector<std::uint8_t>& wire, std::size_t at,
                                          std::size_t expected, const char* what) {
    const std::uint8_t* frame = wire.data() + at;
    const std::size_t size = wire.size() - at;
    const std::size_t frame_size = ZSTD_findFrameCompressedSize(frame, size);
    if (ZSTD_isError(frame_size))
        fail(std::string("damaged or cut short ") + what +
             " (zstd: " + ZSTD_getErrorName(frame_size) + ")");
    if (frame_size != size) fail(std::to_string(size - frame_size) + " bytes after the " + what);
    const unsigned long long content = ZSTD_getFrameContentSize(frame, size);
    if (content != expected)
        fail(std::string(what) + " holds " +
             (content == ZSTD_CONTENTSIZE_UNKNOWN || content == ZSTD_CONTENTSIZE_ERROR
                  ? std::string("an unknown size")
                  : std::to_string(content) + " bytes") +
             ", the header says " + std::to_string(expected));
    std::vector<std::uint8_t> out(expected);
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), frame, size);
    if (ZSTD_isError(n))
        fail(std::string("damaged ") + what + " (zstd: " + ZSTD_getErrorName(n) + ")");
    if (n != expected) fail(std::string(what) + " decompressed to the wrong size");
    return out;
}

std::vector<std::uint8_t> frame(PayloadCodec codec, std::size_t cdr_size) {
    std::vector<std::uint8_t> out(kPrefix);
    out[0] = static_cast<std::uint8_t>(codec);
    const auto size = static_cast<std::uint32_t>(cdr_size);
    std::memcpy(out.data() + 1, &size, 4);
    return out;
}

void append(std::vector<std::uint8_t>& out, const std::vector<std::uint8_t>& more) {
    out.insert(out.end(), more.begin(), more.end());
}

std::uint32_t lane(const std::uint8_t* p) {
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

void set_lane(std::uint8_t* p, std::uint32_t v) { std::memcpy(p, &v, 4); }

// The ranges of `cdr` transformed (forward) or restored; the rest as it is.
std::vector<std::uint8_t> shuffled(const std::vector<std::uint8_t>& cdr,
                                   const std::vector<Range>& ranges, bool forward) {
    std::vector<std::uint8_t> out = cdr;
    std::vector<std::uint8_t> work;
    for (const Range& r : ranges) {
        const std::size_t n = r.length / r.stride;
        const std::uint8_t* in = cdr.data() + r.offset;
        work.assign(in, in + r.length);
        if (forward) {
            if (r.delta)
                for (std::size_t i = n; i-- > 1;)
                    for (std::size_t b = 0; b < r.stride; b += 4)
                        set_lane(&work[i * r.stride + b],
                                 lane(in + i * r.stride + b) - lane(in + (i - 1) * r.stride + b));
            shuffle_bytes(work.data(), n, r.stride, out.data() + r.offset);
        } else {
            unshuffle_bytes(in, n, r.stride, work.data());
            if (r.delta)
                for (std::size_t i = 1; i < n; ++i)
                    for (std::size_t b = 0; b < r.stride; b += 4)
                        set_lane(&work[i * r.stride + b], lane(&work[i * r.stride + b]) +
                                                              lane(&work[(i - 1) * r.stride + b]));
            std::copy(work.begin(), work.end(), out.begin() + r.offset);
        }
    }
    return out;
}

}  // namespace

const char* codec_name(PayloadCodec codec) {
    switch (codec) {
        case PayloadCodec::kStored:
            return "stored";
        case PayloadCodec::kZstd:
            return "zstd";
        case PayloadCodec::kShuffled:
            return "shuffled+zstd";
        case PayloadCodec::kLocalMap:
            return "local-map-columns+zstd";
    }
    return "?";
}

PayloadCodec payload_codec(const std::vector<std::uint8_t>& wire) {
    if (wire.empty()) fail("empty");
    if (wire[0] > static_cast<std::uint8_t>(PayloadCodec::kLocalMap))
        fail("unknown codec " + std::to_string(wire[0]) + " (a newer robot?)");
    return static_cast<PayloadCodec>(wire[0]);
}

std::vector<std::uint8_t> encode_payload(const std::string& dds_type,
                                         const std::vector<std::uint8_t>& cdr,
                                         const PayloadCodecConfig& config) {
    if (config.level < 1 || config.level > ZSTD_maxCLevel())
        fail("zstd level " + std::to_string(config.level) + " is not 1.." +
             std::to_string(ZSTD_maxCLevel()));
    if (cdr.size() > kMaxCdr) fail("message of " + std::to_string(cdr.size()) + " B over 1 GiB");
    std::vector<std::uint8_t> out;
    if (dds_type == kLocalMapType) {
        if (const auto columns = local_map_to_columns(cdr)) {
            out = frame(PayloadCodec::kLocalMap, cdr.size());
            const std::uint32_t size = static_cast<std::uint32_t>(columns->size());
            out.insert(out.end(), reinterpret_cast<const std::uint8_t*>(&size),
                       reinterpret_cast<const std::uint8_t*>(&size) + 4);
            append(out, zstd_compress(columns->data(), columns->size(), config.level));
        }
    } else if (dds_type == kKeyframeType) {
        const std::vector<Range> ranges = keyframe_ranges(cdr);
        if (!ranges.empty()) {
            out = frame(PayloadCodec::kShuffled, cdr.size());
            out.push_back(static_cast<std::uint8_t>(ranges.size()));
            for (const Range& r : ranges) {
                std::uint8_t b[kRangeBytes];
                std::memcpy(b, &r.offset, 4);
                std::memcpy(b + 4, &r.length, 4);
                std::memcpy(b + 8, &r.stride, 2);
                b[10] = r.delta;
                out.insert(out.end(), b, b + kRangeBytes);
            }
            const std::vector<std::uint8_t> s = shuffled(cdr, ranges, true);
            append(out, zstd_compress(s.data(), s.size(), config.level));
        }
    }
    if (out.empty()) {
        out = frame(PayloadCodec::kZstd, cdr.size());
        append(out, zstd_compress(cdr.data(), cdr.size(), config.level));
    }
    if (out.size() >= kPrefix + cdr.size()) {  // incompressible (or tiny): as it is
        out = frame(PayloadCodec::kStored, cdr.size());
        append(out, cdr);
    }
    return out;
}

std::vector<std::uint8_t> decode_payload(const std::string& dds_type,
                                         const std::vector<std::uint8_t>& wire) {
    const PayloadCodec codec = payload_codec(wire);
    if (wire.size() < kPrefix)
        fail("cut short in its header (" + std::to_string(wire.size()) + " B)");
    std::uint32_t size;
    std::memcpy(&size, wire.data() + 1, 4);
    if (size > kMaxCdr) fail("states a message of " + std::to_string(size) + " B (over 1 GiB)");
    switch (codec) {
        case PayloadCodec::kStored:
            if (wire.size() - kPrefix != size)
                fail("stored message of " + std::to_string(wire.size() - kPrefix) +
                     " B, the header says " + std::to_string(size));
            return std::vector<std::uint8_t>(wire.begin() + kPrefix, wire.end());
        case PayloadCodec::kZstd:
            return zstd_decompress(wire, kPrefix, size, "zstd frame");
        case PayloadCodec::kShuffled: {
            if (wire.size() < kPrefix + 1) fail("cut short before its ranges");
            const std::size_t count = wire[kPrefix];
            std::size_t at = kPrefix + 1;
            if (wire.size() - at < count * kRangeBytes) fail("cut short in its ranges");
            std::vector<Range> ranges(count);
            for (Range& r : ranges) {
                std::memcpy(&r.offset, wire.data() + at, 4);
                std::memcpy(&r.length, wire.data() + at + 4, 4);
                std::memcpy(&r.stride, wire.data() + at + 8, 2);
                r.delta = wire[at + 10];
                at += kRangeBytes;
                if (r.stride == 0 || r.length % r.stride != 0 || r.delta > 1 ||
                    (r.delta && r.stride % 4 != 0) || r.offset > size || r.length > size - r.offset)
                    fail("a shuffled range [" + std::to_string(r.offset) + ", +" +
                         std::to_string(r.length) + ") / " + std::to_string(r.stride) +
                         " outside the message of " + std::to_string(size) + " B");
            }
            return shuffled(zstd_decompress(wire, at, size, "zstd frame"), ranges, false);
        }
        case PayloadCodec::kLocalMap: {
            if (dds_type != kLocalMapType)
                fail(std::string("local map columns given as ") + dds_type);
            if (wire.size() < kPrefix + 4) fail("cut short before its column size");
            std::uint32_t columns_size;
            std::memcpy(&columns_size, wire.data() + kPrefix, 4);
            if (columns_size > kMaxCdr) fail("states columns of over 1 GiB");
            std::vector<std::uint8_t> cdr = local_map_from_columns(
                zstd_decompress(wire, kPrefix + 4, columns_size, "zstd frame"));
            if (cdr.size() != size)
                fail("local map of " + std::to_string(cdr.size()) + " B, the header says " +
                     std::to_string(size));
            return cdr;
        }
    }
    fail("unknown codec");
}

}  // namespace ltm::link
