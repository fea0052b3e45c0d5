#pragma once
// What a site version is made of, file by file, as the base station offers it to a robot
// (site_sync, issue 26): every regular file under SITE/versions/vNNNN (the map's manifest, graph,
// keyframe chunks and local maps, the maintained map, version.txt) with its size and FNV-1a 64
// hash, the version's number and the chunk size the transfer cuts files into. Unchanged files of
// a version are hard links to the previous version's, so a robot that holds the previous version
// holds them already: it compares these hashes with its own files (held_files.hpp) and asks only
// for the rest.
//   ltm_site_offer 1
//   version <number>
//   chunk_size <bytes>
//   file <size> <hash: 16 hex digits> <path relative to the version folder>
//   end <number of files>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ltm::site_sync {

struct VersionFile {
    std::string path;  // relative to the version folder: "map/local_maps/lm_....bin"
    std::uint64_t size = 0;
    std::uint64_t hash = 0;  // FNV-1a 64 of the file (the map manifest's hash)
};

// One chunk of one file of an offer: chunk c of file f covers bytes [c * chunk_size, ...).
struct ChunkRef {
    std::uint32_t file = 0;
    std::uint32_t chunk = 0;
    bool operator==(const ChunkRef& o) const { return file == o.file && chunk == o.chunk; }
    bool operator<(const ChunkRef& o) const {
        return file != o.file ? file < o.file : chunk < o.chunk;
    }
};

struct VersionOffer {
    std::uint32_t number = 0;        // the version's number at the base station (v0007: 7)
    std::uint32_t chunk_size = 0;    // bytes
    std::vector<VersionFile> files;  // sorted by path

    std::uint32_t chunks(std::size_t file) const;  // at least 1 (an empty file: one empty chunk)
    std::uint64_t total_bytes() const;
    // Where chunk `c` of file `f` starts and how long it is.
    std::uint64_t chunk_offset(ChunkRef c) const { return std::uint64_t(c.chunk) * chunk_size; }
    std::uint32_t chunk_length(ChunkRef c) const;
    bool valid(ChunkRef c) const { return c.file < files.size() && c.chunk < chunks(c.file); }
};

// FNV-1a 64 of a file's bytes (read in pieces) and its size. Throws common::IoError.
std::uint64_t hash_file(const std::string& path, std::uint64_t* size);

// The files of a version folder, hashed. Throws common::IoError (one line) for a folder that
// cannot be read or holds something other than folders and regular files.
VersionOffer scan_version(const std::string& dir, std::uint32_t number, std::uint32_t chunk_size);

std::string write_offer(const VersionOffer& offer);
// Throws common::FormatError naming the line for text that is not a whole, valid offer (paths
// absolute, with "..", empty parts or white space are refused: the robot writes where they say).
VersionOffer parse_offer(const std::string& text);
// The offer's identity: FNV-1a 64 of its text (two offers with the same files and number match).
std::uint64_t offer_id(const std::string& offer_text);

// The bytes of one chunk, read from the version folder. Throws common::IoError.
std::string read_chunk(const std::string& version_dir, const VersionOffer& offer, ChunkRef c);
// FNV-1a 64 of a chunk's bytes (what a chunk message carries and the robot checks).
std::uint64_t chunk_hash(const void* bytes, std::size_t size);

std::string hex64(std::uint64_t v);

}  // namespace ltm::site_sync
