#include "common/core/byte_io.hpp"

#include <cstdio>

#include "common/core/crc32.hpp"

namespace ltm::common {

std::uint32_t ByteWriter::crc_of(std::size_t from) const {
    return crc32(out_->data() + from, out_->size() - from);
}

ByteReader::ByteReader(std::string source, const void* data, std::size_t size, std::uint64_t base)
    : source_(std::move(source)),
      data_(static_cast<const std::uint8_t*>(data)),
      size_(size),
      base_(base),
      source_size_(base + size) {}

std::string ByteReader::field_name(const char* field) const {
    std::string name = list_ ? list_ : "";
    if (list_ && index_ != kNoIndex) name += "[" + std::to_string(index_) + "]";
    if (field) name += (list_ ? "." : "") + std::string(field);
    return name;
}

void ByteReader::fail(const char* field, const std::string& problem) const {
    fail_at(field, offset(), problem);
}

void ByteReader::fail_at(const char* field, std::uint64_t at, const std::string& problem) const {
    throw FormatError(source_, field_name(field), at, problem);
}

void ByteReader::need(std::uint64_t n, const char* field) const {
    if (size_ - pos_ < n) {
        fail(field, "truncated: needs " + std::to_string(n) + " bytes, " +
                        std::to_string(size_ - pos_) + " left");
    }
}

void ByteReader::str(std::string& s, const char* field) {
    const std::uint32_t n = get<std::uint32_t>(field);
    const std::uint8_t* p = span(n, field);
    s.assign(reinterpret_cast<const char*>(p), n);
}

void ByteReader::raw(void* out, std::size_t n, const char* field) {
    const std::uint8_t* p = span(n, field);
    if (n) std::memcpy(out, p, n);
}

const std::uint8_t* ByteReader::span(std::uint64_t n, const char* field) {
    need(n, field);
    const std::uint8_t* p = data_ + pos_;
    pos_ += static_cast<std::size_t>(n);
    return p;
}

ByteReader ByteReader::block32(const char* field) {
    const std::uint32_t n = get<std::uint32_t>(field);
    const std::uint64_t at = offset();
    ByteReader r(source_, span(n, field), n, at);
    r.item(list_, index_);
    r.source_size_ = source_size_;
    return r;
}

ByteReader ByteReader::section_reader(const std::string& name) {
    // Section errors name the section itself, whatever item is being read.
    const std::uint64_t start = offset();
    std::uint32_t length = 0;
    if (remaining() < 4) {
        throw FormatError(source_, name + " length", start,
                          "truncated: needs 4 bytes, " + std::to_string(remaining()) + " left");
    }
    std::memcpy(&length, here(), 4);
    pos_ += 4;
    if (remaining() < std::size_t(length) + 4) {
        throw FormatError(source_, name, start,
                          "section of " + std::to_string(length) + " bytes does not fit in the " +
                              std::to_string(remaining()) +
                              " bytes left (truncated or damaged length)");
    }
    const std::uint8_t* body = here();
    const std::uint64_t body_offset = offset();
    pos_ += length;
    std::uint32_t stored = 0;
    std::memcpy(&stored, here(), 4);
    pos_ += 4;
    const std::uint32_t computed = crc32(body, length);
    if (stored != computed) {
        throw FormatError(source_, name, body_offset,
                          "checksum mismatch over bytes " + std::to_string(body_offset) + "-" +
                              std::to_string(body_offset + length) + " (stored " + hex32(stored) +
                              ", computed " + hex32(computed) + ")");
    }
    ByteReader r(source_, body, length, body_offset);
    r.source_size_ = source_size_;
    return r;
}

void ByteReader::expect_end(const char* what) const {
    if (pos_ != size_) {
        throw FormatError(source_, what, offset(),
                          std::to_string(size_ - pos_) + " unexpected bytes after the end");
    }
}

std::string hex32(std::uint32_t v) {
    char buf[9];
    std::snprintf(buf, sizeof(buf), "%08x", v);
    return buf;
}

}  // namespace ltm::common
