#include "recorder/core/compression.hpp"

#include <gtest/gtest.h>

#include <random>

#include "common/core/io_error.hpp"

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
            ASSERT_NO_THROW(comp.compress(in.data(), in.size(), packed));
            if (kind != Compression::kNone && n == 5000000u) {
                EXPECT_LT(packed.size(), n / 2);
            }
            ASSERT_NO_THROW(
                decompress(compression_name(kind), packed.data(), packed.size(), n, out))
                << compression_name(kind) << " " << n;
            EXPECT_EQ(out, in);
        }
    }
}

TEST(Compression, DetectsDamageAndWrongSizes) {
    const auto in = sample(100000, 3);
    for (const Compression kind : {Compression::kZstd, Compression::kLz4}) {
        Compressor comp(kind, 0);
        std::vector<std::uint8_t> packed, out;
        ASSERT_NO_THROW(comp.compress(in.data(), in.size(), packed));
        const std::string name = compression_name(kind);
        try {
            decompress(name, packed.data(), packed.size(), in.size() + 1, out);
            ADD_FAILURE() << "a wrong size was accepted";
        } catch (const common::FormatError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(name + ": ", 0), 0u) << e.what();
        }
        EXPECT_THROW(decompress(name, packed.data(), packed.size() / 2, in.size(), out),
                     common::FormatError);
        auto broken = packed;
        broken[0] ^= 0xFF;  // frame magic
        EXPECT_THROW(decompress(name, broken.data(), broken.size(), in.size(), out),
                     common::FormatError);
    }
    std::vector<std::uint8_t> out;
    try {
        decompress("bz2", in.data(), in.size(), in.size(), out);
        ADD_FAILURE() << "bz2 was accepted";
    } catch (const common::FormatError& e) {
        EXPECT_STREQ(e.what(), "bz2: unsupported compression");
    }
    EXPECT_THROW(decompress("zstd", in.data(), 10, std::uint64_t{1} << 40, out),
                 common::FormatError);
}

}  // namespace
}  // namespace ltm::recorder
