#include "mapping/core/binary_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"
#include "recorder/core/crc32.hpp"

namespace ltm::mapping {
namespace {

std::string format_error(const std::string& file, const std::string& field, std::uint64_t offset,
                         const std::string& problem) {
    std::ostringstream s;
    s << file << ": " << field << " at byte " << offset << ": " << problem;
    return s.str();
}

void write_all(int fd, const std::string& bytes, const std::string& path) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw common::IoError(path, std::string("write failed: ") + std::strerror(errno));
        }
        done += std::size_t(n);
    }
}

void fsync_dir(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd < 0) return;  // best effort: some file systems do not open folders
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

MapFormatError::MapFormatError(const std::string& file, const std::string& field,
                               std::uint64_t offset, const std::string& problem)
    : std::runtime_error(format_error(file, field, offset, problem)),
      file_(file),
      field_(field),
      offset_(offset) {}

MapFormatError::MapFormatError(const std::string& file, const std::string& problem)
    : std::runtime_error(file + ": " + problem), file_(file) {}

void ByteWriter::put_bytes(const void* data, std::size_t n) {
    const std::size_t at = bytes_.size();
    bytes_.resize(at + n);
    if (n) std::memcpy(&bytes_[at], data, n);
}

void ByteWriter::put_vec3f(const Eigen::Vector3f& v) {
    for (int i = 0; i < 3; ++i) put<float>(v[i]);
}
void ByteWriter::put_vec3d(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) put<double>(v[i]);
}
void ByteWriter::put_vec3i(const Eigen::Vector3i& v) {
    for (int i = 0; i < 3; ++i) put<std::int32_t>(v[i]);
}
void ByteWriter::put_pose(const Eigen::Isometry3d& T) {
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) put<double>(T.matrix()(r, c));
    }
}

void ByteWriter::begin_section() {
    put<std::uint32_t>(0);  // length, patched by end_section()
    section_start_ = bytes_.size();
}

void ByteWriter::end_section() {
    const std::uint32_t length = std::uint32_t(bytes_.size() - section_start_);
    std::memcpy(&bytes_[section_start_ - 4], &length, 4);
    put<std::uint32_t>(recorder::crc32(bytes_.data() + section_start_, length));
    section_start_ = std::string::npos;
}

ByteReader::ByteReader(std::string file, const char* data, std::size_t size, std::uint64_t base)
    : file_(std::move(file)), data_(data), size_(size), base_(base) {}

void ByteReader::fail(const std::string& field, const std::string& problem) const {
    throw MapFormatError(file_, field, offset(), problem);
}

void ByteReader::fail_at(const std::string& field, std::uint64_t at,
                         const std::string& problem) const {
    throw MapFormatError(file_, field, at, problem);
}

void ByteReader::need(std::size_t n, const std::string& field) const {
    if (size_ - pos_ < n) {
        std::ostringstream s;
        s << "truncated: needs " << n << " bytes, " << (size_ - pos_) << " left";
        fail(field, s.str());
    }
}

double ByteReader::get_f64(const std::string& field) {
    const std::uint64_t at = offset();
    const double v = get<double>(field);
    if (!std::isfinite(v)) fail_at(field, at, "not a finite number");
    return v;
}

float ByteReader::get_f32(const std::string& field) {
    const std::uint64_t at = offset();
    const float v = get<float>(field);
    if (!std::isfinite(v)) fail_at(field, at, "not a finite number");
    return v;
}

Eigen::Vector3f ByteReader::get_vec3f(const std::string& field) {
    Eigen::Vector3f v;
    for (int i = 0; i < 3; ++i) v[i] = get_f32(field);
    return v;
}

Eigen::Vector3d ByteReader::get_vec3d(const std::string& field) {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = get_f64(field);
    return v;
}

Eigen::Vector3i ByteReader::get_vec3i(const std::string& field) {
    Eigen::Vector3i v;
    for (int i = 0; i < 3; ++i) v[i] = get<std::int32_t>(field);
    return v;
}

Eigen::Isometry3d ByteReader::get_pose(const std::string& field) {
    const std::uint64_t at = offset();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) T.matrix()(r, c) = get_f64(field);
    }
    const Eigen::Matrix3d R = T.linear();
    if ((R.transpose() * R - Eigen::Matrix3d::Identity()).norm() > 1e-5 || R.determinant() < 0.0) {
        fail_at(field, at, "rotation is not orthonormal");
    }
    return T;
}

void ByteReader::get_bytes(void* out, std::size_t n, const std::string& field) {
    need(n, field);
    if (n) std::memcpy(out, data_ + pos_, n);
    pos_ += n;
}

ByteReader ByteReader::section(const std::string& name) {
    const std::uint64_t start = offset();
    const std::uint32_t length = get<std::uint32_t>(name + " length");
    if (remaining() < std::size_t(length) + 4) {
        std::ostringstream s;
        s << "section of " << length << " bytes does not fit in the " << remaining()
          << " bytes left (truncated or damaged length)";
        fail_at(name, start, s.str());
    }
    const char* body = data_ + pos_;
    const std::uint64_t body_offset = offset();
    pos_ += length;
    const std::uint32_t stored = get<std::uint32_t>(name + " checksum");
    const std::uint32_t computed = recorder::crc32(body, length);
    if (stored != computed) {
        std::ostringstream s;
        s << "checksum mismatch over bytes " << body_offset << "-" << (body_offset + length)
          << " (stored " << hex32(stored) << ", computed " << hex32(computed) << ")";
        fail_at(name, body_offset, s.str());
    }
    return ByteReader(file_, body, length, body_offset);
}

void ByteReader::expect_end(const std::string& what) const {
    if (pos_ != size_) {
        std::ostringstream s;
        s << (size_ - pos_) << " unexpected bytes after the end";
        fail(what, s.str());
    }
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
    const std::string tmp = path + ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) throw common::IoError(tmp, std::string("cannot create: ") + std::strerror(errno));
    try {
        write_all(fd, bytes, tmp);
        if (::fsync(fd) != 0) {
            throw common::IoError(tmp, std::string("fsync failed: ") + std::strerror(errno));
        }
    } catch (...) {
        ::close(fd);
        std::remove(tmp.c_str());
        throw;
    }
    if (::close(fd) != 0) {
        std::remove(tmp.c_str());
        throw common::IoError(tmp, std::string("close failed: ") + std::strerror(errno));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(tmp.c_str());
        throw common::IoError(path, "rename from .tmp failed: " + why);
    }
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    fsync_dir(parent.empty() ? std::string(".") : parent.string());
}

std::string read_file(const std::string& path, const std::string& name_in_errors) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MapFormatError(name_in_errors, "cannot open (missing or unreadable)");
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw MapFormatError(name_in_errors, "read error");
    return s.str();
}

std::uint32_t crc32_of(const std::string& bytes) {
    return recorder::crc32(bytes.data(), bytes.size());
}

std::uint64_t fnv1a64(const std::string& bytes) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const char c : bytes) {
        h ^= std::uint8_t(c);
        h *= 0x100000001b3ull;
    }
    return h;
}

std::string hex64(std::uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

std::string hex32(std::uint32_t v) {
    char buf[9];
    std::snprintf(buf, sizeof(buf), "%08x", v);
    return buf;
}

}  // namespace ltm::mapping
