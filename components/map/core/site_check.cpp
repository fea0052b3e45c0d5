#include "map/core/site_check.hpp"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/core/crc32.hpp"
#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/map_manifest.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kChunk = 1 << 20;

std::string hex64(std::uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// The FNV-1a 64 of a file read in pieces, and its size; false when it cannot be read.
bool hash_file(const fs::path& path, std::uint64_t* hash, std::uint64_t* size) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::vector<char> buf(kChunk);
    std::uint64_t h = kMapFileHashInit, n = 0;
    while (in) {
        in.read(buf.data(), std::streamsize(buf.size()));
        const std::size_t got = std::size_t(in.gcount());
        h = map_file_hash_update(h, buf.data(), got);
        n += got;
    }
    if (in.bad()) return false;
    *hash = h;
    *size = n;
    return true;
}

}  // namespace

std::string check_map_dir(const std::string& dir) {
    const fs::path root(dir);
    std::error_code ec;
    if (!fs::is_directory(root, ec)) return dir + ": no map directory";
    if (!fs::exists(root / kManifestFile, ec)) return dir + "/" + kManifestFile + ": missing";
    Manifest manifest;
    try {
        manifest =
            parse_manifest(common::read_file((root / kManifestFile).string(), kManifestFile));
    } catch (const common::IoError& e) {
        return e.what();
    }
    for (const ManifestEntry& e : manifest.files) {
        std::uint64_t hash = 0, size = 0;
        if (!hash_file(root / e.file, &hash, &size)) return e.file + ": missing or unreadable";
        if (size != e.size)
            return e.file + ": " + std::to_string(size) + " bytes, the manifest says " +
                   std::to_string(e.size) + " (truncated or replaced)";
        if (hash != e.hash)
            return e.file + ": file checksum FNV-1a " + hex64(hash) +
                   " differs from the manifest's " + hex64(e.hash);
    }
    return "";
}

std::string check_maintained_map_file(const std::string& path, bool must_exist) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return must_exist ? path + ": missing" : "";
    const std::string name = fs::path(path).filename().string();
    std::ifstream in(path, std::ios::binary);
    if (!in) return name + ": cannot be read";
    char head[12];
    if (!in.read(head, sizeof head) || std::memcmp(head, "LTMMAINT", 8) != 0)
        return name + ": not a maintained map (no LTMMAINT signature)";
    std::uint64_t at = sizeof head;
    std::vector<char> buf(kChunk);
    for (int section = 0;; ++section) {
        std::uint32_t length = 0;
        in.read(reinterpret_cast<char*>(&length), sizeof length);
        if (in.gcount() == 0 && in.eof()) return section == 0 ? name + ": no sections" : "";
        if (in.gcount() != sizeof length)
            return name + ": section " + std::to_string(section) + " at byte " +
                   std::to_string(at) + ": truncated";
        std::uint32_t crc = common::crc32_init();
        for (std::uint32_t left = length; left > 0;) {
            const std::uint32_t n = std::min<std::uint32_t>(left, std::uint32_t(buf.size()));
            if (!in.read(buf.data(), n))
                return name + ": section " + std::to_string(section) + " at byte " +
                       std::to_string(at) + ": truncated (" + std::to_string(length) +
                       " bytes announced)";
            crc = common::crc32_update(crc, buf.data(), n);
            left -= n;
        }
        std::uint32_t stored = 0;
        if (!in.read(reinterpret_cast<char*>(&stored), sizeof stored))
            return name + ": section " + std::to_string(section) + " at byte " +
                   std::to_string(at) + ": truncated (no CRC)";
        if (common::crc32_final(crc) != stored)
            return name + ": section " + std::to_string(section) + " at byte " +
                   std::to_string(at) + ": CRC-32 mismatch (damaged)";
        at += 8 + std::uint64_t(length);
    }
}

}  // namespace ltm::map
