#include "map/core/site_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "common/core/io_error.hpp"

namespace ltm::map {
namespace {

// The pid the holder wrote ("" while it has not yet).
std::string holder(int fd) {
    char buf[32] = {};
    const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
    if (n <= 0) return "";
    std::string s(buf, std::size_t(n));
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
}

}  // namespace

SiteLock::SiteLock(const std::string& path) : path_(path) {
    std::error_code ec;
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    if (ec)
        throw common::IoError(parent.string(), "cannot create the site folder: " + ec.message());
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw common::IoError(path, std::string("cannot open: ") + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int error = errno;
        const std::string pid = holder(fd_);
        ::close(fd_);
        fd_ = -1;
        if (error == EWOULDBLOCK)
            throw common::IoError(
                path, "the site is in use by " +
                          (pid.empty() ? std::string("another process") : "pid " + pid) +
                          " (a session runs on it); stop that one first");
        throw common::IoError(path, std::string("cannot lock: ") + std::strerror(error));
    }
    const std::string text = std::to_string(::getpid()) + "\n";
    if (::ftruncate(fd_, 0) != 0 ||
        ::pwrite(fd_, text.data(), text.size(), 0) != ssize_t(text.size())) {
        const int error = errno;
        release();
        throw common::IoError(path, std::string("cannot write the lock: ") + std::strerror(error));
    }
    ::fsync(fd_);
}

SiteLock::~SiteLock() { release(); }

void SiteLock::release() {
    if (fd_ < 0) return;
    if (::ftruncate(fd_, 0) != 0) {
        // The pid stays in the file; the lock itself goes with the descriptor.
    }
    ::close(fd_);
    fd_ = -1;
}

}  // namespace ltm::map
