#include "site/core/version_files.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/io_error.hpp"
#include "map/core/map_manifest.hpp"

namespace ltm::site_sync {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMagic = "ltm_site_offer 1";
constexpr std::uint32_t kMaxChunk = 16u << 20;

bool safe_path(const std::string& p) {
    if (p.empty() || p.front() == '/' || p.back() == '/') return false;
    for (const char c : p)
        if (c <= ' ' || c == 127) return false;
    std::size_t start = 0;
    while (start <= p.size()) {
        const std::size_t end = std::min(p.find('/', start), p.size());
        const std::string part = p.substr(start, end - start);
        if (part.empty() || part == "." || part == "..") return false;
        start = end + 1;
    }
    return true;
}

bool parse_u64(const std::string& s, std::uint64_t* v, int base = 10) {
    if (s.empty() || s.size() > 20) return false;
    std::uint64_t n = 0;
    for (const char c : s) {
        int d = -1;
        if (c >= '0' && c <= '9') d = c - '0';
        if (base == 16 && c >= 'a' && c <= 'f') d = c - 'a' + 10;
        if (d < 0) return false;
        const std::uint64_t next = n * std::uint64_t(base) + std::uint64_t(d);
        if (next / std::uint64_t(base) != n) return false;  // overflow
        n = next;
    }
    *v = n;
    return true;
}

}  // namespace

std::string hex64(std::uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

std::uint32_t VersionOffer::chunks(std::size_t file) const {
    const std::uint64_t size = files[file].size;
    return size == 0 ? 1u : std::uint32_t((size + chunk_size - 1) / chunk_size);
}

std::uint64_t VersionOffer::total_bytes() const {
    std::uint64_t n = 0;
    for (const VersionFile& f : files) n += f.size;
    return n;
}

std::uint32_t VersionOffer::chunk_length(ChunkRef c) const {
    const std::uint64_t start = chunk_offset(c), size = files[c.file].size;
    return start >= size ? 0u : std::uint32_t(std::min<std::uint64_t>(chunk_size, size - start));
}

std::uint64_t hash_file(const std::string& path, std::uint64_t* size) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw common::IoError(path, "cannot be read");
    std::vector<char> buf(1 << 20);
    std::uint64_t h = map::kMapFileHashInit, n = 0;
    while (in) {
        in.read(buf.data(), std::streamsize(buf.size()));
        const std::size_t got = std::size_t(in.gcount());
        h = map::map_file_hash_update(h, buf.data(), got);
        n += got;
    }
    if (in.bad()) throw common::IoError(path, "read failed");
    if (size) *size = n;
    return h;
}

VersionOffer scan_version(const std::string& dir, std::uint32_t number, std::uint32_t chunk_size) {
    if (chunk_size == 0 || chunk_size > kMaxChunk)
        throw common::IoError(dir, "chunk size must be 1 B to 16 MiB");
    VersionOffer offer;
    offer.number = number;
    offer.chunk_size = chunk_size;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw common::IoError(dir, "no version folder");
    fs::recursive_directory_iterator it(dir, ec), end;
    if (ec) throw common::IoError(dir, "cannot be listed: " + ec.message());
    for (; it != end; it.increment(ec)) {
        if (ec) throw common::IoError(dir, "cannot be listed: " + ec.message());
        const fs::file_status st = it->symlink_status(ec);
        if (fs::is_directory(st)) continue;
        const std::string rel = fs::relative(it->path(), dir, ec).generic_string();
        if (!fs::is_regular_file(st) || !safe_path(rel))
            throw common::IoError(it->path().string(),
                                  "not a regular file with a plain name: a version holds only "
                                  "folders and files");
        VersionFile f;
        f.path = rel;
        f.hash = hash_file(it->path().string(), &f.size);
        offer.files.push_back(f);
    }
    std::sort(offer.files.begin(), offer.files.end(),
              [](const VersionFile& a, const VersionFile& b) { return a.path < b.path; });
    return offer;
}

std::string write_offer(const VersionOffer& offer) {
    std::ostringstream out;
    out << kMagic << "\nversion " << offer.number << "\nchunk_size " << offer.chunk_size << "\n";
    for (const VersionFile& f : offer.files)
        out << "file " << f.size << " " << hex64(f.hash) << " " << f.path << "\n";
    out << "end " << offer.files.size() << "\n";
    return out.str();
}

VersionOffer parse_offer(const std::string& text) {
    VersionOffer offer;
    std::istringstream in(text);
    std::string line;
    std::size_t number = 0;
    bool ended = false;
    const auto fail = [&](const std::string& problem) {
        throw common::FormatError("site offer", "line " + std::to_string(number) + ": " + problem);
    };
    while (std::getline(in, line)) {
        ++number;
        if (ended) fail("text after the end line");
        std::istringstream words(line);
        std::vector<std::string> w;
        for (std::string s; words >> s;) w.push_back(s);
        std::uint64_t a = 0, b = 0;
        if (number == 1) {
            if (line != kMagic) fail("not a site offer (expected '" + std::string(kMagic) + "')");
        } else if (number == 2) {
            if (w.size() != 2 || w[0] != "version" || !parse_u64(w[1], &a) || a == 0 ||
                a > 0xffffffffull)
                fail("expected 'version <number>'");
            offer.number = std::uint32_t(a);
        } else if (number == 3) {
            if (w.size() != 2 || w[0] != "chunk_size" || !parse_u64(w[1], &a) || a == 0 ||
                a > kMaxChunk)
                fail("expected 'chunk_size <1 B to 16 MiB>'");
            offer.chunk_size = std::uint32_t(a);
        } else if (!w.empty() && w[0] == "file") {
            if (w.size() != 4 || !parse_u64(w[1], &a) || w[2].size() != 16 ||
                !parse_u64(w[2], &b, 16))
                fail("expected 'file <size> <16 hex digits> <path>'");
            if (!safe_path(w[3])) fail("path '" + w[3] + "' is not a plain relative path");
            if (!offer.files.empty() && !(offer.files.back().path < w[3]))
                fail("files not in ascending order of path");
            offer.files.push_back({w[3], a, b});
        } else if (!w.empty() && w[0] == "end") {
            if (w.size() != 2 || !parse_u64(w[1], &a) || a != offer.files.size())
                fail("end line does not count the files");
            ended = true;
        } else {
            fail("unknown line");
        }
    }
    if (!ended) fail("cut short (no end line)");
    return offer;
}

std::uint64_t offer_id(const std::string& offer_text) { return map::map_file_hash(offer_text); }

std::string read_chunk(const std::string& version_dir, const VersionOffer& offer, ChunkRef c) {
    if (!offer.valid(c)) throw common::IoError(version_dir, "no such chunk");
    const std::string path = version_dir + "/" + offer.files[c.file].path;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw common::IoError(path, "cannot be read");
    std::string bytes(offer.chunk_length(c), '\0');
    in.seekg(std::streamoff(offer.chunk_offset(c)));
    in.read(bytes.data(), std::streamsize(bytes.size()));
    if (std::size_t(in.gcount()) != bytes.size())
        throw common::IoError(path, "shorter than the offer says");
    return bytes;
}

std::uint64_t chunk_hash(const void* bytes, std::size_t size) {
    return map::map_file_hash_update(map::kMapFileHashInit, static_cast<const char*>(bytes), size);
}

}  // namespace ltm::site_sync
