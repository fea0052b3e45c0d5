#include "maintenance/core/packed_scan.hpp"

#include <zstd.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "common/core/io_error.hpp"

namespace ltm::maintenance {
namespace {

constexpr int kColumns = 3;              // x, y, z
constexpr std::size_t kValueBytes = 4;   // a float
constexpr std::size_t kPointBytes = 12;  // kColumns * kValueBytes
constexpr const char* kSource = "packed scan";

std::uint32_t bits_of(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

float float_of(std::uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

}  // namespace

PackedScan pack_points(const std::vector<Eigen::Vector3f>& points, int level) {
    if (level < 1 || level > ZSTD_maxCLevel())
        throw std::invalid_argument("pack_points: zstd level " + std::to_string(level) +
                                    " out of 1.." + std::to_string(ZSTD_maxCLevel()));
    const std::size_t n = points.size();
    PackedScan out;
    out.count = std::uint32_t(n);
    // Byte b of column c of point i at ((c * 4 + b) * n + i).
    std::vector<std::uint8_t> shuffled(n * kPointBytes);
    for (int c = 0; c < kColumns; ++c) {
        std::uint32_t previous = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t u = bits_of(points[i][c]);
            const std::uint32_t d = u - previous;
            previous = u;
            for (std::size_t b = 0; b < kValueBytes; ++b)
                shuffled[(std::size_t(c) * kValueBytes + b) * n + i] = std::uint8_t(d >> (8 * b));
        }
    }
    out.bytes.resize(ZSTD_compressBound(shuffled.size()));
    const std::size_t size =
        ZSTD_compress(out.bytes.data(), out.bytes.size(), shuffled.data(), shuffled.size(), level);
    if (ZSTD_isError(size))
        throw std::runtime_error(std::string("pack_points: zstd: ") + ZSTD_getErrorName(size));
    out.bytes.resize(size);
    out.bytes.shrink_to_fit();
    return out;
}

std::vector<Eigen::Vector3f> unpack_points(const PackedScan& packed) {
    const std::size_t n = packed.count;
    std::vector<std::uint8_t> shuffled(n * kPointBytes);
    const unsigned long long stated =
        ZSTD_getFrameContentSize(packed.bytes.data(), packed.bytes.size());
    if (stated == ZSTD_CONTENTSIZE_ERROR || stated == ZSTD_CONTENTSIZE_UNKNOWN)
        throw common::FormatError(kSource, "not a zstd frame");
    if (stated != shuffled.size())
        throw common::FormatError(kSource, "holds " + std::to_string(stated) + " bytes, " +
                                               std::to_string(n) + " points need " +
                                               std::to_string(shuffled.size()));
    const std::size_t size =
        ZSTD_decompress(shuffled.data(), shuffled.size(), packed.bytes.data(), packed.bytes.size());
    if (ZSTD_isError(size))
        throw common::FormatError(kSource, std::string("zstd: ") + ZSTD_getErrorName(size));
    if (size != shuffled.size())
        throw common::FormatError(kSource, "cut short: " + std::to_string(size) + " of " +
                                               std::to_string(shuffled.size()) + " bytes");
    std::vector<Eigen::Vector3f> points(n);
    for (int c = 0; c < kColumns; ++c) {
        std::uint32_t previous = 0;
        for (std::size_t i = 0; i < n; ++i) {
            std::uint32_t d = 0;
            for (std::size_t b = 0; b < kValueBytes; ++b)
                d |= std::uint32_t(shuffled[(std::size_t(c) * kValueBytes + b) * n + i]) << (8 * b);
            previous += d;
            points[i][c] = float_of(previous);
        }
    }
    return points;
}

}  // namespace ltm::maintenance
