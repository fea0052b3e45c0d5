#include "common/core/streamed_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "common/core/io_error.hpp"

namespace ltm::common {

AtomicFileWriter::AtomicFileWriter(std::string path)
    : path_(std::move(path)), tmp_(path_ + ".tmp") {
    fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd_ < 0) throw IoError(tmp_, std::string("cannot create: ") + std::strerror(errno));
}

AtomicFileWriter::~AtomicFileWriter() {
    if (fd_ < 0) return;
    ::close(fd_);
    std::remove(tmp_.c_str());
}

void AtomicFileWriter::append(const void* bytes, std::size_t size) {
    if (fd_ < 0) throw IoError(tmp_, "written after commit");
    const char* p = static_cast<const char*>(bytes);
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::write(fd_, p + done, size - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw IoError(tmp_, std::string("write failed: ") + std::strerror(errno));
        }
        done += std::size_t(n);
    }
    size_ += size;
}

void AtomicFileWriter::commit() {
    if (fd_ < 0) throw IoError(tmp_, "committed twice");
    const int fd = fd_;
    fd_ = -1;
    const auto fail = [&](const std::string& what) {
        const std::string why = std::strerror(errno);
        std::remove(tmp_.c_str());
        throw IoError(tmp_, what + ": " + why);
    };
    if (::fsync(fd) != 0) {
        ::close(fd);
        fail("fsync failed");
    }
    if (::close(fd) != 0) fail("close failed");
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0) fail("rename failed");
    const std::filesystem::path parent = std::filesystem::path(path_).parent_path();
    const std::string dir = parent.empty() ? std::string(".") : parent.string();
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (dfd >= 0) {  // best effort: some file systems do not open folders
        ::fsync(dfd);
        ::close(dfd);
    }
}

SectionFileReader::SectionFileReader(const std::string& path, std::string name_in_errors)
    : in_(path, std::ios::binary), name_(std::move(name_in_errors)) {
    if (!in_) throw IoError(name_, "cannot open (missing or unreadable)");
}

std::vector<std::uint8_t> SectionFileReader::bytes(std::size_t n, const char* field) {
    std::vector<std::uint8_t> out(n);
    in_.read(reinterpret_cast<char*>(out.data()), std::streamsize(n));
    const auto got = std::size_t(in_.gcount());
    if (got != n) {
        if (in_.bad()) throw IoError(name_, "read error");
        throw FormatError(
            name_, field, offset_ + got,
            "truncated: needs " + std::to_string(n) + " bytes, " + std::to_string(got) + " left");
    }
    offset_ += n;
    return out;
}

const std::vector<std::uint8_t>& SectionFileReader::next_section(const char* name) {
    section_at_ = offset_;
    const std::vector<std::uint8_t> head = bytes(4, (std::string(name) + " length").c_str());
    std::uint32_t length = 0;
    std::memcpy(&length, head.data(), 4);
    // The length is checked against what the file holds before it is allocated.
    const std::streampos here = in_.tellg();
    in_.seekg(0, std::ios::end);
    const std::uint64_t size = std::uint64_t(in_.tellg());
    in_.seekg(here);
    if (offset_ + std::uint64_t(length) + 4 > size) {
        throw FormatError(name_, name, section_at_,
                          "section of " + std::to_string(length) + " bytes does not fit in the " +
                              std::to_string(size - offset_) +
                              " bytes left (truncated or damaged length)");
    }
    section_ = head;
    const std::vector<std::uint8_t> rest = bytes(std::size_t(length) + 4, name);
    section_.insert(section_.end(), rest.begin(), rest.end());
    return section_;
}

ByteReader SectionFileReader::reader() const {
    return ByteReader(name_, section_.data(), section_.size(), section_at_);
}

bool SectionFileReader::at_end() { return in_.peek() == std::char_traits<char>::eof(); }

}  // namespace ltm::common
