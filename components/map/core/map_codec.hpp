#pragma once
// The binary files of a saved map (format 1, 2 or 3, map_data.hpp; little-endian), each a magic, a
// version and checksummed sections (common/core/byte_io.hpp). Each record is described once, in
// map_codec.cpp, and that description both writes and reads it:
//   local map: header (node, session, id, revision, anchor, grid, box, voxel size, counts),
//              observation times, voxels in sections of up to 4096 (index, centre, normal, point
//              count, planarity, stability, life record);
//   graph:     header (revision, counts), nodes and edges in sections of up to 4096;
//   keyframes: header (first index, count, descriptor settings; format 2: then the localisation
//              descriptor settings), one section a keyframe (ids, stamp, poses, Scan Context
//              descriptor; format 2: then the ScanContext++ localisation descriptor, which may be
//              empty (0 rings, 0 sectors); optional points).
// Local map and graph files are the same in every format but for the version field; keyframe files
// of format 3 are format 2's but for it. Every decode accepts formats 1 to 3 (and returns the
// file's), and refuses any other version.
// Decoding validates every field and throws MapFormatError naming the file, field and offset
// ("local_maps/lm_3.bin: voxels[17].normal at byte 1290: neither zero nor a unit vector").
#include <string>
#include <vector>

#include "map/core/map_data.hpp"

namespace ltm::map {

// The format a map is saved in (map_data.hpp): 1 without localisation descriptors, else 3 when it
// records sessions, else 2.
std::uint32_t map_format_for(const places::ScanContextConfig& localisation_descriptor_config,
                             bool records_sessions = false);

std::string encode_local_map(const StoredLocalMap& map,
                             std::uint32_t version = kRowMapFormatVersion);
StoredLocalMap decode_local_map(const std::string& bytes, const std::string& file,
                                std::uint32_t* version = nullptr);

std::string encode_graph(std::uint64_t revision, const std::vector<PoseGraphNode>& nodes,
                         const std::vector<PoseGraphEdge>& edges,
                         std::uint32_t version = kRowMapFormatVersion);
void decode_graph(const std::string& bytes, const std::string& file, std::uint64_t* revision,
                  std::vector<PoseGraphNode>* nodes, std::vector<PoseGraphEdge>* edges,
                  std::uint32_t* version = nullptr);

// The descriptor settings of a keyframe file's header.
struct DescriptorSettings {
    places::ScanContextConfig loop;  // MapData::descriptor_config
    places::ScanContextConfig localisation =
        no_localisation_descriptors();  // none: a format-1 file
};

// keyframes[first, first + count) of the list, in format `version` (0:
// map_format_for(settings.localisation); 1 only without localisation descriptors).
std::string encode_keyframes(const DescriptorSettings& settings,
                             const std::vector<std::shared_ptr<const StoredKeyframe>>& keyframes,
                             std::size_t first, std::size_t count, std::uint32_t version = 0);
// Returns the keyframes; *first receives the index of the first one. The descriptor shapes (kind,
// rings, sectors) must equal `expected`'s (when not null, they are checked; a format-1 file has
// no localisation descriptors). *version and *settings, when not null, receive the file's.
std::vector<std::shared_ptr<const StoredKeyframe>> decode_keyframes(
    const std::string& bytes, const std::string& file, const DescriptorSettings* expected,
    std::uint64_t* first, std::uint32_t* version = nullptr, DescriptorSettings* settings = nullptr);

}  // namespace ltm::map
