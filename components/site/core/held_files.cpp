#include "site/core/held_files.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "common/core/io_error.hpp"
#include "map/core/site_store.hpp"
#include "site/core/version_files.hpp"

namespace ltm::site_sync {

namespace fs = std::filesystem;

void HeldFiles::add_dir(const std::string& dir) {
    std::error_code ec;
    fs::recursive_directory_iterator it(dir, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
        if (!it->is_regular_file(ec) || it->is_symlink(ec)) continue;
        struct stat st {};
        if (::stat(it->path().c_str(), &st) != 0) continue;
        const auto inode = std::make_pair(std::uint64_t(st.st_dev), std::uint64_t(st.st_ino));
        if (inodes_seen_.count(inode)) continue;
        inodes_seen_[inode] = true;
        try {
            std::uint64_t size = 0;
            const std::uint64_t hash = hash_file(it->path().string(), &size);
            bytes_hashed_ += size;
            by_content_.emplace(std::make_pair(size, hash), it->path().string());
        } catch (const common::IoError&) {
            // Unreadable: not held; the transfer asks for it.
        }
    }
}

void HeldFiles::add_site(const std::string& site_dir) {
    for (const map::SiteVersion& v : map::SiteStore(site_dir).versions())
        if (v.intact) add_dir(v.dir);
}

const std::string* HeldFiles::find(std::uint64_t size, std::uint64_t hash) const {
    const auto it = by_content_.find(std::make_pair(size, hash));
    return it == by_content_.end() ? nullptr : &it->second;
}

}  // namespace ltm::site_sync
