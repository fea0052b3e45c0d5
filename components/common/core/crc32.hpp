#pragma once
// CRC-32 (ISO-HDLC, polynomial 0xEDB88320, as zlib and the MCAP specification use).
#include <cstddef>
#include <cstdint>

namespace ltm::common {

// Running CRC: start from crc32_init(), feed bytes with crc32_update(), read with crc32_final().
constexpr std::uint32_t crc32_init() { return 0xFFFFFFFFu; }
std::uint32_t crc32_update(std::uint32_t state, const void* data, std::size_t size);
constexpr std::uint32_t crc32_final(std::uint32_t state) { return state ^ 0xFFFFFFFFu; }

// One-shot CRC of a buffer.
inline std::uint32_t crc32(const void* data, std::size_t size) {
    return crc32_final(crc32_update(crc32_init(), data, size));
}

}  // namespace ltm::common
