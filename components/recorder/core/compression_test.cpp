#include "recorder/core/compression.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ltm::recorder {
namespace {

std::vector<std::uint8_t> sample(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> d(n);
    for (std::size_t i = 0; i < n; ++i) d[i] = i % 4 == 0 ? static_cast<std::uint8_t>(rng()) : 7;
    return d;
}

TEST(Compression, Names) {
    Compression c;
    ASSERT_TRUE(parse_compression("lz4", c));
    EXPECT_EQ(c, Compression::kLz4);
    ASSERT_TRUE(parse_compression("none", c));
    EXPECT_EQ(c, Compression::kNone);
    EXPECT_FALSE(parse_compression("gzip", c));
    EXPECT_STREQ(compression_name(Compression::kZstd), "zstd");
    EXPECT_STREQ(compression_name(Compression::kNone), "");
}

TEST(Compression, RoundTripsEveryKind) {
    for (const Compression kind : {Compression::kNone, Compression::kZstd, Compression::kLz4}) {
        Compressor comp(kind, kind == Compression::kZstd ? 3 : 0);
        for (std::size_t n : {0u, 1u, 1000u, 5000000u}) {
            const auto in = sample(n, static_cast<std::uint32_t>(n));
            std::vector<std::uint8_t> packed, out;
            std::string err;
            ASSERT_TRUE(comp.compress(in.data(), in.size(), packed, err)) << err;
            if (kind != Compression::kNone && n == 5000000u) {
                EXPECT_LT(packed.size(), n / 2);
            }
            ASSERT_TRUE(
                decompress(compression_name(kind), packed.data(), packed.size(), n, out, err))
                << compression_name(kind) << " " << n << ": " << err;
            EXPECT_EQ(out, in);
        }
    }
}

TEST(Compression, DetectsDamageAndWrongSizes) {
    const auto in = sample(100000, 3);
    for (const Compression kind : {Compression::kZstd, Compression::kLz4}) {
        Compressor comp(kind, 0);
        std::vector<std::uint8_t> packed, out;
        std::string err;
        ASSERT_TRUE(comp.compress(in.data(), in.size(), packed, err));
        EXPECT_FALSE(decompress(compression_name(kind), packed.data(), packed.size(), in.size() + 1,
                                out, err));
        EXPECT_FALSE(err.empty());
        EXPECT_FALSE(decompress(compression_name(kind), packed.data(), packed.size() / 2, in.size(),
                                out, err));
        err.clear();
        auto broken = packed;
        broken[0] ^= 0xFF;  // frame magic
        EXPECT_FALSE(
            decompress(compression_name(kind), broken.data(), broken.size(), in.size(), out, err));
        EXPECT_FALSE(err.empty());
    }
    std::vector<std::uint8_t> out;
    std::string err;
    EXPECT_FALSE(decompress("bz2", in.data(), in.size(), in.size(), out, err));
    EXPECT_NE(err.find("bz2"), std::string::npos);
    EXPECT_FALSE(decompress("zstd", in.data(), 10, std::uint64_t{1} << 40, out, err));
}

}  // namespace
}  // namespace ltm::recorder
