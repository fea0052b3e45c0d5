#pragma once
// The files a robot already holds, by content: every file of its site's intact versions, indexed
// by size and FNV-1a 64 hash (site_sync, issue 26). A file of a new version with the same size
// and hash need not cross the link: it is hard-linked from here. Hard links are hashed once (one
// inode, one read).
#include <cstdint>
#include <map>
#include <string>
#include <utility>

namespace ltm::site_sync {

class HeldFiles {
  public:
    // Every regular file under `dir`, hashed. Unreadable files are left out (not held).
    void add_dir(const std::string& dir);
    // Every intact version of the site (map/core/site_store.hpp: checked first).
    void add_site(const std::string& site_dir);
    // A file with this size and hash, or nullptr.
    const std::string* find(std::uint64_t size, std::uint64_t hash) const;
    std::size_t size() const { return by_content_.size(); }
    std::uint64_t bytes_hashed() const { return bytes_hashed_; }

  private:
    std::map<std::pair<std::uint64_t, std::uint64_t>, std::string> by_content_;
    std::map<std::pair<std::uint64_t, std::uint64_t>, bool> inodes_seen_;  // (device, inode)
    std::uint64_t bytes_hashed_ = 0;
};

}  // namespace ltm::site_sync
