#pragma once
// A block of columns compressed with zstd (issue 26: the map and the maintained state on disk):
// the shared code of the compact file formats (maintained map regions, local maps).
//
// A ColumnBlock collects numbered columns of fixed-width values; planes() lays each column out
// grouped by byte position (all low bytes, ..., all high bytes, so that zstd sees runs of similar
// bytes), one after another, and the caller compresses that as one zstd frame (zstd_compress).
// Lossless and deterministic: the same columns give the same bytes (zstd at a fixed level, the
// same library), so a file whose content did not change
// stays byte-identical (site versions hard-link such files; the link sends only changed files).
// What a column holds (a value, or its difference to a prediction) is the caller's choice.
//
// ColumnReader takes the frame back apart; every read is bounds-checked and a damaged frame is a
// common::FormatError of one line naming the source and the field.
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "common/core/io_error.hpp"

namespace ltm::common {

// zstd level of the map files: zstd's default. Not tuned on the columns; on whole format-2/3
// files the command-line zstd at level 9 was 2-5 % smaller than at 3, and slower.
constexpr int kColumnZstdLevel = 3;

// Compressed frame of `n` bytes; `level` 1..19. Throws std::runtime_error (zstd failing).
std::vector<std::uint8_t> zstd_compress(const std::uint8_t* data, std::size_t n, int level);
// The frame's content, which must be exactly `expected` bytes. Throws FormatError(source, field).
std::vector<std::uint8_t> zstd_decompress(const std::uint8_t* data, std::size_t n,
                                          std::size_t expected, const std::string& source,
                                          const char* field);

// Writing: columns of numbers, appended to in any order, packed in the order first used.
class ColumnBlock {
  public:
    // Column `c` (an index the caller keeps, 0..columns-1) of `width` bytes a value.
    explicit ColumnBlock(const std::vector<std::size_t>& widths);

    template <class T>
    void put(std::size_t column, T v) {
        static_assert(std::is_arithmetic<T>::value, "numbers only");
        check_width(column, sizeof(T));
        const auto* b = reinterpret_cast<const std::uint8_t*>(&v);
        columns_[column].insert(columns_[column].end(), b, b + sizeof(T));
    }
    // Every column's values counted (the reader needs them to find the columns).
    std::vector<std::uint64_t> counts() const;
    // The columns grouped by byte position, in column order (uncompressed).
    std::vector<std::uint8_t> planes() const;

  private:
    void check_width(std::size_t column, std::size_t width) const;
    std::vector<std::size_t> widths_;
    std::vector<std::vector<std::uint8_t>> columns_;
};

// Reading the planes back: column c holds counts[c] values of widths[c] bytes.
class ColumnReader {
  public:
    // Throws FormatError when the counts do not add up to the bytes.
    ColumnReader(std::vector<std::uint8_t> planes, const std::vector<std::size_t>& widths,
                 const std::vector<std::uint64_t>& counts, std::string source);

    // The next value of `column` (FormatError naming `field` when the column is used up).
    template <class T>
    T get(std::size_t column, const char* field) {
        static_assert(std::is_arithmetic<T>::value, "numbers only");
        const std::uint8_t* b = take(column, sizeof(T), field);
        T v;
        std::memcpy(&v, b, sizeof(T));
        return v;
    }
    // Values of `column` not read yet.
    std::uint64_t left(std::size_t column) const;
    // Throws FormatError when a column has values left (the counts said more than was read).
    void expect_end(const char* what) const;
    const std::string& source() const { return source_; }

  private:
    // Checks and advances; the value's bytes.
    const std::uint8_t* take(std::size_t column, std::size_t width, const char* field);
    std::vector<std::vector<std::uint8_t>> columns_;  // unshuffled: values one after another
    std::vector<std::size_t> widths_;
    std::vector<std::uint64_t> next_;
    std::string source_;
};

}  // namespace ltm::common
