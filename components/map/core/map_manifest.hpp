#pragma once
// manifest.txt of a map directory (map_store.hpp): what the map is made of, one line a fact,
//   ltm_map <format version>
//   revision <n>
//   descriptor <kind 0|1> <rings> <sectors> <max_range> <min_range> <sensor_height>
//   localisation_descriptor <kind 0|1> <rings> <sectors> <max_range> <min_range> <sensor_height>
//                                                      (format 2 and 3)
//   session <id> <first_stamp> <last_stamp> <local_maps_added> <local_maps_updated> [<robot>]
//                                                      (format 3: one a session, ids ascending;
//                                                      the robot's name when several built it)
//   graph <file> <size> <hash>
//   keyframes <file> <size> <hash> <first> <count>     (any number of these two)
//   local_map <node> <file> <size> <hash>
//   end <number of file entries>
// Hashes are FNV-1a 64 of the file, 16 lower-case hex digits. The layout is described once, in
// map_manifest.cpp, and that description both writes and parses it.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "map/core/map_data.hpp"

namespace ltm::map {

inline constexpr const char* kManifestFile = "manifest.txt";

struct ManifestEntry {
    std::string kind;  // graph, keyframes, local_map
    std::string file;  // relative to the map directory
    std::uint64_t size = 0;
    std::uint64_t hash = 0;              // FNV-1a 64 of the file
    std::uint64_t node = 0;              // local_map
    std::uint64_t first = 0, count = 0;  // keyframes
};

struct Manifest {
    // Parsed: 1, 2 or 3. Written: 1 without localisation descriptors, else 3 with sessions, else 2
    // (map_data.hpp).
    std::uint32_t version = kRowMapFormatVersion;
    std::uint64_t revision = 0;
    places::ScanContextConfig descriptor;
    // Written in format 2 only; a format-1 manifest parses as no_localisation_descriptors().
    places::ScanContextConfig localisation_descriptor = no_localisation_descriptors();
    std::vector<SessionRecord> sessions;  // format 3 (written only with localisation descriptors)
    std::vector<ManifestEntry> files;     // exactly one graph
};

// FNV-1a 64 of a file's bytes (what the manifest names files by and checks them with); the
// running form hashes a file read in pieces: start from kMapFileHashInit.
inline constexpr std::uint64_t kMapFileHashInit = 0xcbf29ce484222325ull;
inline std::uint64_t map_file_hash_update(std::uint64_t h, const char* bytes, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) {
        h ^= std::uint8_t(bytes[i]);
        h *= 0x100000001b3ull;
    }
    return h;
}
inline std::uint64_t map_file_hash(const std::string& bytes) {
    return map_file_hash_update(kMapFileHashInit, bytes.data(), bytes.size());
}

std::string write_manifest(const Manifest& manifest);
// Throws MapFormatError naming the line and its byte offset ("manifest.txt: line 2 at byte 10:
// ...") when the text is not a whole, valid manifest (of format 1, 2 or 3).
Manifest parse_manifest(const std::string& text);

}  // namespace ltm::map
