#pragma once
// Reading and writing plain little-endian CDR (XCDR1, encapsulation CDR_LE: what Cyclone DDS 0.10
// writes for ltm's final types) without the generated types: the link's payload codec and the
// run report read messages this way. Alignment is relative to the end of the 4-byte encapsulation
// header; 8-byte values align to 8. Every read is bounds-checked: false once the data ran out (the
// cursor stays failed).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace ltm::common {

// True when `cdr` starts with the CDR_LE encapsulation header: 00 01, then the options, whose low
// two bits count the padding bytes appended to make the size a multiple of 4 (Cyclone sets them).
inline bool is_cdr_le(const std::vector<std::uint8_t>& cdr) {
    return cdr.size() >= 4 && cdr[0] == 0 && cdr[1] == 1 && cdr[2] == 0 && (cdr[3] & ~3) == 0;
}

constexpr std::size_t kCdrHeader = 4;

class CdrReader {
  public:
    CdrReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    bool ok() const { return ok_; }
    std::size_t pos() const { return pos_; }

    bool align(std::size_t a) {
        const std::size_t rel = pos_ - kCdrHeader;
        return skip((a - rel % a) % a);
    }
    bool skip(std::size_t n) {
        if (!ok_ || n > size_ - pos_) return ok_ = false;
        pos_ += n;
        return true;
    }
    template <class T>
    bool read(T& v) {
        if (!align(sizeof(T)) || sizeof(T) > size_ - pos_) return ok_ = false;
        std::memcpy(&v, data_ + pos_, sizeof(T));
        pos_ += sizeof(T);
        return true;
    }
    // A string: its length (with the NUL) and the bytes.
    bool skip_string() {
        std::uint32_t n = 0;
        return read(n) && skip(n);
    }
    // A string, without its NUL.
    bool read_string(std::string& s) {
        std::uint32_t n = 0;
        if (!read(n) || n == 0 || n > size_ - pos_) return ok_ = false;
        s.assign(reinterpret_cast<const char*>(data_ + pos_), n - 1);
        pos_ += n;
        return true;
    }
    // A sequence of `element`-byte primitives: its count, then the elements; `offset` is where
    // the elements start.
    bool sequence(std::size_t element, std::uint32_t& count, std::size_t& offset) {
        if (!read(count)) return false;
        if (count > 0 && !align(element)) return false;
        offset = pos_;
        if (count > (size_ - pos_) / element) return ok_ = false;
        return skip(count * element);
    }

  private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = kCdrHeader;
    bool ok_ = true;
};

class CdrWriter {
  public:
    explicit CdrWriter(std::vector<std::uint8_t>& out) : out_(out) {}

    void align(std::size_t a) {
        const std::size_t rel = out_.size() - kCdrHeader;
        out_.resize(out_.size() + (a - rel % a) % a, 0);
    }
    template <class T>
    void write(const T& v) {
        align(sizeof(T));
        bytes(&v, sizeof(T));
    }
    void bytes(const void* p, std::size_t n) {
        const auto* b = static_cast<const std::uint8_t*>(p);
        out_.insert(out_.end(), b, b + n);
    }

  private:
    std::vector<std::uint8_t>& out_;
};

}  // namespace ltm::common
