#include "common/core/column_block.hpp"

#include <zstd.h>

#include <stdexcept>

namespace ltm::common {

std::vector<std::uint8_t> zstd_compress(const std::uint8_t* data, std::size_t n, int level) {
    std::vector<std::uint8_t> out(ZSTD_compressBound(n));
    const std::size_t size = ZSTD_compress(out.data(), out.size(), data, n, level);
    if (ZSTD_isError(size))
        throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(size));
    out.resize(size);
    return out;
}

std::vector<std::uint8_t> zstd_decompress(const std::uint8_t* data, std::size_t n,
                                          std::size_t expected, const std::string& source,
                                          const char* field) {
    const unsigned long long stated = ZSTD_getFrameContentSize(data, n);
    if (stated == ZSTD_CONTENTSIZE_ERROR || stated == ZSTD_CONTENTSIZE_UNKNOWN)
        throw FormatError(source, field, 0, "not a zstd frame");
    if (stated != expected)
        throw FormatError(source, field, 0,
                          "the zstd frame holds " + std::to_string(stated) + " bytes, " +
                              std::to_string(expected) + " expected");
    std::vector<std::uint8_t> out(expected);
    const std::size_t size = ZSTD_decompress(out.data(), out.size(), data, n);
    if (ZSTD_isError(size))
        throw FormatError(source, field, 0, std::string("zstd: ") + ZSTD_getErrorName(size));
    if (size != expected)
        throw FormatError(source, field, 0,
                          "the zstd frame is cut short: " + std::to_string(size) + " of " +
                              std::to_string(expected) + " bytes");
    return out;
}

ColumnBlock::ColumnBlock(const std::vector<std::size_t>& widths)
    : widths_(widths), columns_(widths.size()) {}

void ColumnBlock::check_width(std::size_t column, std::size_t width) const {
    if (column >= widths_.size() || widths_[column] != width)
        throw std::logic_error("ColumnBlock: column " + std::to_string(column) +
                               " written with a value of " + std::to_string(width) + " bytes");
}

std::vector<std::uint64_t> ColumnBlock::counts() const {
    std::vector<std::uint64_t> out;
    for (std::size_t c = 0; c < columns_.size(); ++c)
        out.push_back(columns_[c].size() / widths_[c]);
    return out;
}

std::vector<std::uint8_t> ColumnBlock::planes() const {
    std::size_t total = 0;
    for (const auto& c : columns_) total += c.size();
    std::vector<std::uint8_t> out(total);
    std::size_t at = 0;
    for (std::size_t c = 0; c < columns_.size(); ++c) {
        const std::size_t w = widths_[c], n = columns_[c].size() / w;
        const std::uint8_t* in = columns_[c].data();
        for (std::size_t b = 0; b < w; ++b)
            for (std::size_t i = 0; i < n; ++i) out[at + b * n + i] = in[i * w + b];
        at += columns_[c].size();
    }
    return out;
}

ColumnReader::ColumnReader(std::vector<std::uint8_t> planes, const std::vector<std::size_t>& widths,
                           const std::vector<std::uint64_t>& counts, std::string source)
    : columns_(widths.size()),
      widths_(widths),
      next_(widths.size(), 0),
      source_(std::move(source)) {
    if (counts.size() != widths.size())
        throw FormatError(source_, "columns", 0,
                          std::to_string(counts.size()) + " column counts for " +
                              std::to_string(widths.size()) + " columns");
    std::uint64_t at = 0;
    for (std::size_t c = 0; c < widths.size(); ++c) {
        const std::uint64_t w = widths[c], n = counts[c];
        if (n > planes.size() || n * w > planes.size() - at)
            throw FormatError(source_, "columns", at,
                              "column " + std::to_string(c) + " of " + std::to_string(n) +
                                  " values runs past the " + std::to_string(planes.size()) +
                                  " bytes");
        std::vector<std::uint8_t>& col = columns_[c];
        col.resize(std::size_t(n * w));
        for (std::uint64_t b = 0; b < w; ++b)
            for (std::uint64_t i = 0; i < n; ++i) col[i * w + b] = planes[at + b * n + i];
        at += n * w;
    }
    if (at != planes.size())
        throw FormatError(source_, "columns", at,
                          std::to_string(planes.size() - at) + " bytes after the last column");
}

std::uint64_t ColumnReader::left(std::size_t column) const {
    return columns_.at(column).size() / widths_.at(column) - next_.at(column);
}

const std::uint8_t* ColumnReader::take(std::size_t column, std::size_t width, const char* field) {
    if (column >= widths_.size() || widths_[column] != width)
        throw std::logic_error("ColumnReader: column " + std::to_string(column) +
                               " read as a value of " + std::to_string(width) + " bytes");
    if (left(column) == 0)
        throw FormatError(source_, field, 0,
                          "column " + std::to_string(column) + " used up (" +
                              std::to_string(next_[column]) + " values)");
    return columns_[column].data() + (next_[column]++) * width;
}

void ColumnReader::expect_end(const char* what) const {
    for (std::size_t c = 0; c < widths_.size(); ++c)
        if (left(c) != 0)
            throw FormatError(
                source_, what, 0,
                std::to_string(left(c)) + " values left in column " + std::to_string(c));
}

}  // namespace ltm::common
