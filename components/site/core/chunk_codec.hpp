#pragma once
// A chunk's wire form (site_sync, issue 26): zstd when that makes it smaller, else the bytes as
// they are. Maintained maps and local maps halve at zstd level 3 (site_week: 134 -> 69 MB), so
// the link carries about half of what the robot stores. Lossless; the robot checks the decoded
// bytes against the offer's length and hash.
#include <cstddef>
#include <cstdint>
#include <string>

namespace ltm::site_sync {

enum class ChunkEncoding : std::uint8_t {
    kPlain = 0,
    kZstd = 1,
};

struct EncodedChunk {
    ChunkEncoding encoding = ChunkEncoding::kPlain;
    std::string data;
};

// level 0: never compressed; 1..19: zstd's level.
EncodedChunk encode_chunk(const std::string& bytes, int level);
// The chunk's bytes, or false when `data` is not a valid encoding of exactly `length` bytes (an
// unknown encoding, a damaged or oversized zstd frame).
bool decode_chunk(std::uint8_t encoding, const std::uint8_t* data, std::size_t size,
                  std::size_t length, std::string* bytes);

}  // namespace ltm::site_sync
