#pragma once
// A minimal CDR writer (XCDR1, little endian, with its 4-byte encapsulation header), for the
// messages the bridge makes itself (the map cloud, the mesh scene): what Cyclone DDS and ROS 2
// write for the same types, so Foxglove decodes them with the advertised ros2msg schema.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace ltm::bridge {

class CdrWriter {
  public:
    CdrWriter() : buffer_{0x00, 0x01, 0x00, 0x00} {}  // CDR_LE, no options

    void u8(std::uint8_t v) { put(v); }
    void boolean(bool v) { put(static_cast<std::uint8_t>(v ? 1 : 0)); }
    void u32(std::uint32_t v) { put(v); }
    void i32(std::int32_t v) { put(v); }
    void f64(double v) { put(v); }
    // A string: its length with the terminating NUL, the bytes, the NUL.
    void string(const std::string& s);
    // A sequence's length (its elements follow).
    void length(std::size_t n) { u32(static_cast<std::uint32_t>(n)); }
    // `size` raw bytes (a uint8 sequence's content).
    void bytes(const void* data, std::size_t size);
    void reserve(std::size_t size) { buffer_.reserve(size); }

    std::size_t size() const { return buffer_.size(); }
    std::vector<std::uint8_t> take() { return std::move(buffer_); }

  private:
    // Alignment counts from the end of the encapsulation header.
    void align(std::size_t n) {
        while ((buffer_.size() - 4) % n != 0) buffer_.push_back(0);
    }
    template <class T>
    void put(T v) {
        static_assert(sizeof(T) <= 8, "a primitive");
        align(sizeof(T));
        const std::size_t at = buffer_.size();
        buffer_.resize(at + sizeof(T));
        std::memcpy(buffer_.data() + at, &v, sizeof(T));  // little-endian hosts (checked in .cpp)
    }

    std::vector<std::uint8_t> buffer_;
};

}  // namespace ltm::bridge
