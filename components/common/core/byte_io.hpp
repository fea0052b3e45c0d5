#pragma once
// Little-endian binary records: the one reader and writer of ltm's binary formats (MCAP records,
// map files). A record layout is written once, as a function template over the I/O object,
//     template <class IO, class R> void io(IO& io, R& record) { io.value(record.id, "id"); ... }
// which ByteWriter runs to write (R const) and ByteReader runs to read (R mutable); checks that
// only make sense when reading go under `if constexpr (IO::kReading)` or io.check().
//
// Every read is bounds-checked. A failure throws FormatError naming the source, the field and
// its byte offset ("local_maps/lm_3.bin: voxels[17].normal at byte 1290: not a unit vector").
// Floating-point values must be finite: NaN and infinity read as damage.
// Sections carry their own length and CRC-32, so damage is located to a section.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "common/core/io_error.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "byte I/O assumes a little-endian host");

namespace ltm::common {

// Appends little-endian fields to a byte vector (its own, or one it is given).
class ByteWriter {
  public:
    static constexpr bool kReading = false;

    ByteWriter() : out_(&own_) {}
    explicit ByteWriter(std::vector<std::uint8_t>& out) : out_(&out) {}
    ByteWriter(const ByteWriter&) = delete;
    ByteWriter& operator=(const ByteWriter&) = delete;

    // Bytes written so far (of the whole buffer, when given one).
    std::uint64_t offset() const { return out_->size(); }
    const std::vector<std::uint8_t>& bytes() const { return *out_; }
    std::vector<std::uint8_t>& bytes() { return *out_; }

    // A number (or an enumeration, as its underlying type). Field names serve the reader.
    template <class T>
    void value(const T& v, const char* /*field*/ = nullptr) {
        static_assert(std::is_arithmetic<T>::value || std::is_enum<T>::value, "numbers only");
        raw(&v, sizeof(T));
    }
    // A uint32 byte length, then the bytes.
    void str(const std::string& s, const char* /*field*/ = nullptr) {
        value(static_cast<std::uint32_t>(s.size()));
        raw(s.data(), s.size());
    }
    void raw(const void* p, std::size_t n, const char* /*field*/ = nullptr) {
        const auto* b = static_cast<const std::uint8_t*>(p);
        out_->insert(out_->end(), b, b + n);
    }

    // A length-prefixed block: begin_length<T>() writes a T placeholder and returns where it is;
    // end_length<T>(at) patches in the number of bytes written since.
    template <class T>
    std::size_t begin_length() {
        value(T(0));
        return out_->size();
    }
    template <class T>
    void end_length(std::size_t at) {
        const T n = static_cast<T>(out_->size() - at);
        std::memcpy(out_->data() + at - sizeof(T), &n, sizeof(T));
    }

    // A section: uint32 length, the bytes `body(*this)` writes, uint32 CRC-32 of those bytes.
    template <class Body>
    void section(const std::string& /*name*/, Body&& body) {
        const std::size_t at = begin_length<std::uint32_t>();
        body(*this);
        end_length<std::uint32_t>(at);
        value(crc_of(at));
    }

    // Reading only; nothing to do when writing.
    void item(const char* /*list*/, std::size_t /*index*/) {}
    void item(const char* /*group*/) {}
    template <class Problem>
    void check(bool /*ok*/, const char* /*field*/, std::uint64_t /*at*/, Problem&&) const {}
    void expect_end(const char* /*what*/) const {}

  private:
    std::uint32_t crc_of(std::size_t from) const;

    std::vector<std::uint8_t> own_;
    std::vector<std::uint8_t>* out_;
};

// Reads little-endian fields from a bounded span of bytes it does not own.
class ByteReader {
  public:
    static constexpr bool kReading = true;

    // `source` names the bytes in errors (a file, "Channel record"); `base` is the offset of
    // data[0] in that source, so that errors give offsets in the source.
    ByteReader(std::string source, const void* data, std::size_t size, std::uint64_t base = 0);

    std::uint64_t offset() const { return base_ + pos_; }  // of the next byte, in the source
    std::size_t remaining() const { return size_ - pos_; }
    const std::uint8_t* here() const { return data_ + pos_; }
    const std::string& source() const { return source_; }
    // Bytes of the whole source (of the reader that sections and blocks were taken from): bounds
    // counts read from the data before anything is allocated for them.
    std::uint64_t source_size() const { return source_size_; }

    template <class T>
    T get(const char* field) {
        static_assert(std::is_arithmetic<T>::value, "numbers only");
        need(sizeof(T), field);
        T v;
        std::memcpy(&v, data_ + pos_, sizeof(T));
        if constexpr (std::is_floating_point<T>::value) {
            if (!std::isfinite(v)) fail(field, "not a finite number");
        }
        pos_ += sizeof(T);
        return v;
    }
    // The counterpart of ByteWriter::value. An enumeration is read as its underlying type and
    // not checked: describe enumerations with a range check (see io.check).
    template <class T>
    void value(T& v, const char* field = nullptr) {
        if constexpr (std::is_enum<T>::value) {
            v = static_cast<T>(get<std::underlying_type_t<T>>(field));
        } else {
            v = get<T>(field);
        }
    }
    void str(std::string& s, const char* field = nullptr);
    void raw(void* out, std::size_t n, const char* field = nullptr);
    // The next n bytes, in place.
    const std::uint8_t* span(std::uint64_t n, const char* field = nullptr);
    // A uint32 length, then that many bytes: a reader over them (offsets still in the source).
    ByteReader block32(const char* field = nullptr);

    // A section written by ByteWriter::section: checks its length and CRC, runs body over a
    // reader of its bytes, which must read them all.
    template <class Body>
    void section(const std::string& name, Body&& body) {
        ByteReader s = section_reader(name);
        body(s);
        s.expect_end(name.c_str());
    }
    ByteReader section_reader(const std::string& name);

    // Names fields in errors: after item("voxels", 17), field "normal" is "voxels[17].normal";
    // after item("header"), "header.node". A null field names the item itself.
    void item(const char* list, std::size_t index) {
        list_ = list;
        index_ = index;
    }
    void item(const char* group) {
        list_ = group;
        index_ = kNoIndex;
    }
    std::string field_name(const char* field) const;

    // Throws FormatError for `field` at byte `at` unless ok. The problem is a text, or a function
    // that returns it (called only on failure).
    template <class Problem>
    void check(bool ok, const char* field, std::uint64_t at, Problem&& problem) const {
        if (ok) return;
        if constexpr (std::is_invocable<Problem>::value) {
            fail_at(field, at, problem());
        } else {
            fail_at(field, at, problem);
        }
    }
    [[noreturn]] void fail(const char* field, const std::string& problem) const;
    [[noreturn]] void fail_at(const char* field, std::uint64_t at,
                              const std::string& problem) const;
    // Every byte must have been read.
    void expect_end(const char* what) const;

  private:
    static constexpr std::size_t kNoIndex = ~std::size_t(0);
    void need(std::uint64_t n, const char* field) const;

    std::string source_;
    const std::uint8_t* data_;
    std::size_t size_, pos_ = 0;
    std::uint64_t base_;
    std::uint64_t source_size_;
    const char* list_ = nullptr;
    std::size_t index_ = kNoIndex;
};

std::string hex32(std::uint32_t v);  // 8 lower-case hex digits

}  // namespace ltm::common
