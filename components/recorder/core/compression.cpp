#include "recorder/core/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <stdexcept>

#include "common/core/io_error.hpp"

namespace ltm::recorder {
namespace {

// Larger uncompressed sizes are treated as a corrupt chunk header, not allocated.
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{2} << 30;

[[noreturn]] void damaged(const char* compression, const std::string& problem) {
    throw common::FormatError(compression, problem);
}

void decompress_zstd(const std::uint8_t* in, std::size_t n, std::uint64_t size,
                     std::vector<std::uint8_t>& out) {
    const unsigned long long declared = ZSTD_getFrameContentSize(in, n);
    if (declared == ZSTD_CONTENTSIZE_ERROR) damaged("zstd", "not a zstd frame");
    if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != size) {
        damaged("zstd", "the frame holds " + std::to_string(declared) +
                            " bytes, the chunk header says " + std::to_string(size));
    }
    out.resize(size);
    const std::size_t got = ZSTD_decompress(out.data(), out.size(), in, n);
    if (ZSTD_isError(got)) damaged("zstd", ZSTD_getErrorName(got));
    if (got != size) {
        damaged("zstd", "gave " + std::to_string(got) + " bytes, expected " + std::to_string(size));
    }
}

void decompress_lz4(const std::uint8_t* in, std::size_t n, std::uint64_t size,
                    std::vector<std::uint8_t>& out) {
    LZ4F_dctx* ctx = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) {
        throw std::runtime_error("lz4: cannot create a decompression context");
    }
    std::string error;
    out.resize(size);
    std::size_t in_pos = 0, out_pos = 0;
    bool ok = true;
    while (true) {
        std::size_t dst = out.size() - out_pos, src = n - in_pos;
        const std::size_t hint =
            LZ4F_decompress(ctx, out.data() + out_pos, &dst, in + in_pos, &src, nullptr);
        if (LZ4F_isError(hint)) {
            error = LZ4F_getErrorName(hint);
            ok = false;
            break;
        }
        in_pos += src;
        out_pos += dst;
        if (hint == 0) break;  // frame complete
        if (src == 0 && dst == 0) {
            error = out_pos == out.size() ? "the frame holds more bytes than the chunk header says"
                                          : "the frame is cut short";
            ok = false;
            break;
        }
    }
    LZ4F_freeDecompressionContext(ctx);
    if (ok && out_pos != size) {
        error = "gave " + std::to_string(out_pos) + " bytes, expected " + std::to_string(size);
        ok = false;
    }
    if (!ok) damaged("lz4", error);
}

}  // namespace

const char* compression_name(Compression c) {
    switch (c) {
        case Compression::kZstd:
            return "zstd";
        case Compression::kLz4:
            return "lz4";
        case Compression::kNone:
            break;
    }
    return "";
}

bool parse_compression(const std::string& text, Compression& out) {
    if (text == "zstd")
        out = Compression::kZstd;
    else if (text == "lz4")
        out = Compression::kLz4;
    else if (text == "none" || text.empty())
        out = Compression::kNone;
    else
        return false;
    return true;
}

Compressor::Compressor(Compression kind, int level) : kind_(kind), level_(level) {
    if (kind_ == Compression::kZstd) zstd_ctx_ = ZSTD_createCCtx();
}

Compressor::~Compressor() { ZSTD_freeCCtx(static_cast<ZSTD_CCtx*>(zstd_ctx_)); }

void Compressor::compress(const std::uint8_t* in, std::size_t size,
                          std::vector<std::uint8_t>& out) {
    switch (kind_) {
        case Compression::kNone:
            out.assign(in, in + size);
            return;
        case Compression::kZstd: {
            out.resize(ZSTD_compressBound(size));
            const std::size_t got =
                ZSTD_compressCCtx(static_cast<ZSTD_CCtx*>(zstd_ctx_), out.data(), out.size(), in,
                                  size, level_ > 0 ? level_ : 1);
            if (ZSTD_isError(got)) {
                throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(got));
            }
            out.resize(got);
            return;
        }
        case Compression::kLz4: {
            LZ4F_preferences_t prefs{};
            prefs.frameInfo.contentSize = size;
            prefs.frameInfo.blockSizeID = LZ4F_max4MB;
            prefs.compressionLevel = level_ > 0 ? level_ : 0;
            out.resize(LZ4F_compressFrameBound(size, &prefs));
            const std::size_t got = LZ4F_compressFrame(out.data(), out.size(), in, size, &prefs);
            if (LZ4F_isError(got)) {
                throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(got));
            }
            out.resize(got);
            return;
        }
    }
    throw std::runtime_error("unknown compression");
}

void decompress(const std::string& compression, const std::uint8_t* in, std::size_t in_size,
                std::uint64_t size, std::vector<std::uint8_t>& out) {
    const char* name = compression.empty() ? "uncompressed records" : compression.c_str();
    if (size > kMaxChunkBytes)
        damaged(name, "implausible uncompressed size " + std::to_string(size));
    // Neither format expands further than this (lz4: a match byte per 255 output bytes; zstd: a
    // 4-byte RLE block per 128 KiB): a larger claim would only allocate memory for nothing.
    const std::uint64_t max_ratio = compression == "lz4" ? 256 : 32768;
    if (!compression.empty() && size > max_ratio * in_size + (std::uint64_t{128} << 10))
        damaged(name, "uncompressed size " + std::to_string(size) + " is implausible for " +
                          std::to_string(in_size) + " compressed bytes");
    if (compression.empty()) {
        if (in_size != size) {
            damaged(name, "the chunk holds " + std::to_string(in_size) +
                              " bytes, its header says " + std::to_string(size));
        }
        out.assign(in, in + in_size);
    } else if (compression == "zstd") {
        decompress_zstd(in, in_size, size, out);
    } else if (compression == "lz4") {
        decompress_lz4(in, in_size, size, out);
    } else {
        damaged(name, "unsupported compression");
    }
}

}  // namespace ltm::recorder
