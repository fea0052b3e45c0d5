#include "common/core/crc32.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace ltm::common {
namespace {

// Bit-by-bit reference (the definition).
std::uint32_t crc_bitwise(const std::vector<std::uint8_t>& d) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (const std::uint8_t b : d) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
    }
    return c ^ 0xFFFFFFFFu;
}

TEST(Crc32, CheckValue) {
    const char* s = "123456789";
    EXPECT_EQ(crc32(s, 9), 0xCBF43926u);
    EXPECT_EQ(crc32(s, 0), 0u);
}

TEST(Crc32, MatchesBitwiseReferenceAndIsIncremental) {
    std::mt19937 rng(7);
    for (std::size_t n : {1u, 7u, 8u, 9u, 63u, 1000u, 4097u}) {
        std::vector<std::uint8_t> d(n);
        for (auto& b : d) b = static_cast<std::uint8_t>(rng());
        const std::uint32_t ref = crc_bitwise(d);
        EXPECT_EQ(crc32(d.data(), d.size()), ref) << n;
        const std::size_t cut = n / 3;
        std::uint32_t st = crc32_update(crc32_init(), d.data(), cut);
        st = crc32_update(st, d.data() + cut, n - cut);
        EXPECT_EQ(crc32_final(st), ref) << n;
    }
}

}  // namespace
}  // namespace ltm::common
