#include "common/core/file_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"

namespace ltm::common {
namespace {

void write_all(int fd, const char* bytes, std::size_t size, const std::string& path) {
    std::size_t done = 0;
    while (done < size) {
        const ssize_t n = ::write(fd, bytes + done, size - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw IoError(path, std::string("write failed: ") + std::strerror(errno));
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

void sync_folder(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    const int r = ::fsync(fd);
    const int error = errno;
    ::close(fd);
    if (r != 0) throw IoError(dir, std::string("fsync: ") + std::strerror(error));
}

std::string read_file(const std::string& path, const std::string& name_in_errors) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(name_in_errors, "cannot open (missing or unreadable)");
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw IoError(name_in_errors, "read error");
    return s.str();
}

void write_file_atomic(const std::string& path, const void* bytes, std::size_t size) {
    const std::string tmp = path + ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) throw IoError(tmp, std::string("cannot create: ") + std::strerror(errno));
    try {
        write_all(fd, static_cast<const char*>(bytes), size, tmp);
        if (::fsync(fd) != 0) {
            throw IoError(tmp, std::string("fsync failed: ") + std::strerror(errno));
        }
    } catch (...) {
        ::close(fd);
        std::remove(tmp.c_str());
        throw;
    }
    if (::close(fd) != 0) {
        std::remove(tmp.c_str());
        throw IoError(tmp, std::string("close failed: ") + std::strerror(errno));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(tmp.c_str());
        throw IoError(path, "rename from .tmp failed: " + why);
    }
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    fsync_dir(parent.empty() ? std::string(".") : parent.string());
}

}  // namespace ltm::common
