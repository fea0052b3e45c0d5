// A chunk's wire form: lossless, compressed only when smaller, and a damaged or mislabelled
// frame is refused (never decoded to other bytes).
#include "site/core/chunk_codec.hpp"

#include <gtest/gtest.h>

#include <random>

namespace ltm::site_sync {
namespace {

TEST(ChunkCodec, LosslessSmallerOrPlainAndDamageRefused) {
    std::string text;
    for (int i = 0; i < 2000; ++i) text += "voxel " + std::to_string(i % 37) + ";";
    std::mt19937 rng(3);
    std::string noise(8192, '\0');
    for (char& c : noise) c = char(rng());
    for (const std::string& bytes : {text, noise, std::string()}) {
        const EncodedChunk e = encode_chunk(bytes, 3);
        EXPECT_LE(e.data.size(), bytes.size());
        std::string back;
        ASSERT_TRUE(decode_chunk(std::uint8_t(e.encoding),
                                 reinterpret_cast<const std::uint8_t*>(e.data.data()),
                                 e.data.size(), bytes.size(), &back));
        EXPECT_EQ(back, bytes);
    }
    const EncodedChunk z = encode_chunk(text, 3);
    EXPECT_EQ(z.encoding, ChunkEncoding::kZstd);
    EXPECT_LT(z.data.size() * 4, text.size());
    EXPECT_EQ(encode_chunk(noise, 3).encoding, ChunkEncoding::kPlain);  // zstd would not shrink it
    EXPECT_EQ(encode_chunk(text, 0).encoding, ChunkEncoding::kPlain);
    const auto* d = reinterpret_cast<const std::uint8_t*>(z.data.data());
    std::string out;
    EXPECT_FALSE(decode_chunk(1, d, z.data.size(), text.size() + 1, &out));  // wrong length
    EXPECT_FALSE(decode_chunk(7, d, z.data.size(), text.size(), &out));      // unknown encoding
    EXPECT_FALSE(decode_chunk(0, d, z.data.size(), text.size(), &out));      // not plain
    std::string cut = z.data.substr(0, z.data.size() - 4);
    EXPECT_FALSE(decode_chunk(1, reinterpret_cast<const std::uint8_t*>(cut.data()), cut.size(),
                              text.size(), &out));
}

}  // namespace
}  // namespace ltm::site_sync
