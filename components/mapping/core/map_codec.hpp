#pragma once
// The binary files of a saved map (format kMapFormatVersion, little-endian), each a magic, a
// version and checksummed sections (common/core/byte_io.hpp). Each record is described once, in
// map_codec.cpp, and that description both writes and reads it:
//   local map: header (node, session, id, revision, anchor, grid, box, voxel size, counts),
//              observation times, voxels in sections of up to 4096 (index, centre, normal, point
//              count, planarity, stability, life record);
//   graph:     header (revision, counts), nodes and edges in sections of up to 4096;
//   keyframes: header (first index, count, descriptor settings), one section a keyframe (ids,
//              stamp, poses, Scan Context descriptor, optional points).
// Decoding validates every field and throws MapFormatError naming the file, field and offset
// ("local_maps/lm_3.bin: voxels[17].normal at byte 1290: neither zero nor a unit vector").
#include <string>
#include <vector>

#include "mapping/core/map_data.hpp"

namespace ltm::mapping {

std::string encode_local_map(const StoredLocalMap& map);
StoredLocalMap decode_local_map(const std::string& bytes, const std::string& file);

std::string encode_graph(std::uint64_t revision, const std::vector<PoseGraphNode>& nodes,
                         const std::vector<PoseGraphEdge>& edges);
void decode_graph(const std::string& bytes, const std::string& file, std::uint64_t* revision,
                  std::vector<PoseGraphNode>* nodes, std::vector<PoseGraphEdge>* edges);

// keyframes[first, first + count) of the list.
std::string encode_keyframes(const ScanContextConfig& descriptor_config,
                             const std::vector<std::shared_ptr<const StoredKeyframe>>& keyframes,
                             std::size_t first, std::size_t count);
// Returns the keyframes; *first receives the index of the first one; the descriptor settings
// must equal `descriptor_config` (when not null, they are checked).
std::vector<std::shared_ptr<const StoredKeyframe>> decode_keyframes(
    const std::string& bytes, const std::string& file, const ScanContextConfig* descriptor_config,
    std::uint64_t* first);

}  // namespace ltm::mapping
