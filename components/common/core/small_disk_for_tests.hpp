#pragma once
// Tests of a full disk (issue 28): a small tmpfs mounted on a fresh folder, unmounted and removed
// when the object dies. Mounting needs root (CAP_SYS_ADMIN); where it is refused, mounted() is
// false and why() says why, for the test's skip message. Header-only, tests only.
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

namespace ltm::common {

class SmallDisk {
  public:
    // A tmpfs of `bytes` (rounded up to pages by the kernel) on a new folder named after `name`.
    SmallDisk(const std::string& name, std::size_t bytes) {
        namespace fs = std::filesystem;
        path_ = (fs::temp_directory_path() /
                 ("ltm_small_disk_" + name + "_" + std::to_string(::getpid())))
                    .string();
        std::error_code ec;
        fs::remove_all(path_, ec);
        fs::create_directories(path_, ec);
        if (ec) {
            why_ = path_ + ": " + ec.message();
            return;
        }
        const std::string options = "size=" + std::to_string(bytes) + ",mode=0755";
        if (::mount("ltm_small_disk", path_.c_str(), "tmpfs", MS_NOSUID | MS_NODEV,
                    options.c_str()) != 0) {
            why_ = "cannot mount a small tmpfs (needs root): " + std::string(std::strerror(errno));
            return;
        }
        mounted_ = true;
    }
    ~SmallDisk() {
        if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    SmallDisk(const SmallDisk&) = delete;
    SmallDisk& operator=(const SmallDisk&) = delete;

    bool mounted() const { return mounted_; }
    const std::string& why() const { return why_; }
    const std::string& path() const { return path_; }

  private:
    std::string path_, why_;
    bool mounted_ = false;
};

}  // namespace ltm::common
