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
    // Replaces out with the compressed bytes; false (with error set) on failure.
    bool compress(const std::uint8_t* in, std::size_t size, std::vector<std::uint8_t>& out,
                  std::string& error);

  private:
    Compression kind_;
    int level_;
    void* zstd_ctx_ = nullptr;
};

// Decompresses a chunk's records. `compression` is the name read from the file and `size` the
// Chunk's uncompressed_size; out is resized to exactly `size` bytes. On failure returns false
// with a short reason in error (unknown compression, corrupt stream, size mismatch).
bool decompress(const std::string& compression, const std::uint8_t* in, std::size_t in_size,
                std::uint64_t size, std::vector<std::uint8_t>& out, std::string& error);

}  // namespace ltm::recorder
