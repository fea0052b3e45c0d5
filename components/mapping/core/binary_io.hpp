#pragma once
// Little-endian binary records for the map files, with checked reading: every value is read under
// a field name, and a failure names the file, the field and its byte offset
// ("local_maps/lm_3.bin: voxels[17].normal at byte 1290: not a unit vector").
// Sections carry their own length and CRC-32, so damage is located to a section
// ("voxels[4096..8191] (bytes 300112-603215): checksum mismatch").
// Also: atomic file writing (temporary file, fsync, rename, fsync of the directory).
#include <Eigen/Geometry>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace ltm::mapping {

// A damaged or unreadable map file. what() is "file: field at byte N: problem" (one line).
class MapFormatError : public std::runtime_error {
  public:
    MapFormatError(const std::string& file, const std::string& field, std::uint64_t offset,
                   const std::string& problem);
    // For problems that are not about one field (missing file, I/O error).
    MapFormatError(const std::string& file, const std::string& problem);
    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    std::uint64_t offset() const { return offset_; }

  private:
    std::string file_, field_;
    std::uint64_t offset_ = 0;
};

class ByteWriter {
  public:
    template <class T>
    void put(T v) {
        static_assert(std::is_arithmetic<T>::value, "plain numbers only");
        const std::size_t at = bytes_.size();
        bytes_.resize(at + sizeof(T));
        std::memcpy(&bytes_[at], &v, sizeof(T));
    }
    void put_bytes(const void* data, std::size_t n);
    void put_vec3f(const Eigen::Vector3f& v);
    void put_vec3d(const Eigen::Vector3d& v);
    void put_vec3i(const Eigen::Vector3i& v);
    void put_pose(const Eigen::Isometry3d& T);  // 12 doubles: the 3x4 matrix, row-major
    // A section: u32 length, the bytes written until end_section(), u32 CRC-32 of those bytes.
    void begin_section();
    void end_section();
    const std::string& bytes() const { return bytes_; }
    std::string& bytes() { return bytes_; }

  private:
    std::string bytes_;
    std::size_t section_start_ = std::string::npos;
};

class ByteReader {
  public:
    // `file` names the file in errors; `base` is the byte offset of data[0] in that file.
    ByteReader(std::string file, const char* data, std::size_t size, std::uint64_t base = 0);

    std::uint64_t offset() const { return base_ + pos_; }  // of the next byte, in the file
    std::size_t remaining() const { return size_ - pos_; }
    const std::string& file() const { return file_; }

    template <class T>
    T get(const std::string& field) {
        static_assert(std::is_arithmetic<T>::value, "plain numbers only");
        need(sizeof(T), field);
        T v;
        std::memcpy(&v, data_ + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    // Finite floating-point values (NaN and infinity are damage).
    double get_f64(const std::string& field);
    float get_f32(const std::string& field);
    Eigen::Vector3f get_vec3f(const std::string& field);
    Eigen::Vector3d get_vec3d(const std::string& field);
    Eigen::Vector3i get_vec3i(const std::string& field);
    // A rigid transform: finite, with an orthonormal rotation (det +1).
    Eigen::Isometry3d get_pose(const std::string& field);
    void get_bytes(void* out, std::size_t n, const std::string& field);
    // A section written by ByteWriter::begin/end_section: checks its length and CRC, and
    // returns a reader over its bytes (offsets still relative to the file).
    ByteReader section(const std::string& name);

    // Throws MapFormatError for `field` at `at` (default: the current offset).
    [[noreturn]] void fail(const std::string& field, const std::string& problem) const;
    [[noreturn]] void fail_at(const std::string& field, std::uint64_t at,
                              const std::string& problem) const;
    void expect(bool ok, const std::string& field, const std::string& problem) const {
        if (!ok) fail(field, problem);
    }
    // The end of the data must have been reached.
    void expect_end(const std::string& what) const;

  private:
    void need(std::size_t n, const std::string& field) const;

    std::string file_;
    const char* data_;
    std::size_t size_, pos_ = 0;
    std::uint64_t base_;
};

// Writes `bytes` to `path` atomically: PATH.tmp, fsync, rename over PATH, fsync of the folder.
// Throws common::IoError (naming the path) on failure.
void write_file_atomic(const std::string& path, const std::string& bytes);
// The whole file; throws MapFormatError(file, ...) when it cannot be read.
std::string read_file(const std::string& path, const std::string& name_in_errors);
std::uint32_t crc32_of(const std::string& bytes);
std::string hex32(std::uint32_t v);  // 8 lower-case hex digits
// FNV-1a 64 of a whole file: names files and checks them against the manifest. (A CRC-32 of a
// file made of CRC-protected sections would not do: a section's bytes and its own CRC change
// together in a way that leaves the CRC of the whole unchanged.)
std::uint64_t fnv1a64(const std::string& bytes);
std::string hex64(std::uint64_t v);  // 16 lower-case hex digits

}  // namespace ltm::mapping
