#include "site/core/chunk_codec.hpp"

#include <zstd.h>

namespace ltm::site_sync {

EncodedChunk encode_chunk(const std::string& bytes, int level) {
    EncodedChunk out;
    if (level <= 0 || bytes.empty()) {
        out.data = bytes;
        return out;
    }
    std::string z(ZSTD_compressBound(bytes.size()), '\0');
    const std::size_t n = ZSTD_compress(z.data(), z.size(), bytes.data(), bytes.size(), level);
    if (ZSTD_isError(n) || n >= bytes.size()) {
        out.data = bytes;
        return out;
    }
    z.resize(n);
    out.encoding = ChunkEncoding::kZstd;
    out.data = std::move(z);
    return out;
}

bool decode_chunk(std::uint8_t encoding, const std::uint8_t* data, std::size_t size,
                  std::size_t length, std::string* bytes) {
    if (encoding == std::uint8_t(ChunkEncoding::kPlain)) {
        if (size != length) return false;
        bytes->assign(reinterpret_cast<const char*>(data), size);
        return true;
    }
    if (encoding != std::uint8_t(ChunkEncoding::kZstd)) return false;
    const unsigned long long content = ZSTD_getFrameContentSize(data, size);
    if (content != length) return false;
    bytes->assign(length, '\0');
    const std::size_t n = ZSTD_decompress(bytes->data(), length, data, size);
    return !ZSTD_isError(n) && n == length;
}

}  // namespace ltm::site_sync
