#pragma once
// Chunk compression for MCAP: zstd (libzstd) and lz4 frames (liblz4), as the MCAP registry names
// them ("zstd", "lz4"; "" is no compression).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::recorder {

enum class Compression { kNone, kZstd, kLz4 };

// The name written in Chunk records: "", "zstd" or "lz4".
const char* compression_name(Compression c);
// Accepts "none", "" , "zstd", "lz4" (command-line spelling); false for anything else.
bool parse_compression(const std::string& text, Compression& out);

// Compresses whole chunks, reusing its compression context between calls.
class Compressor {
  public:
    // level: zstd level (1..19; <= 0 means 1); lz4: 0 = fast default, > 0 = high-compression
    // level (LZ4HC), which is much slower.
    Compressor(Compression kind, int level);
    ~Compressor();
    Compressor(const Compressor&) = delete;
    Compressor& operator=(const Compressor&) = delete;

    Compression kind() const { return kind_; }
    // Replaces out with the compressed bytes; throws std::runtime_error when the library fails.
    void compress(const std::uint8_t* in, std::size_t size, std::vector<std::uint8_t>& out);

  private:
    Compression kind_;
    int level_;
    void* zstd_ctx_ = nullptr;
};

// Decompresses a chunk's records. `compression` is the name read from the file and `size` the
// Chunk's uncompressed_size; out is resized to exactly `size` bytes. Throws common::FormatError
// ("zstd: the frame is cut short", "bz2: unsupported compression") when the bytes cannot be
// decompressed to that size.
void decompress(const std::string& compression, const std::uint8_t* in, std::size_t in_size,
                std::uint64_t size, std::vector<std::uint8_t>& out);

}  // namespace ltm::recorder
