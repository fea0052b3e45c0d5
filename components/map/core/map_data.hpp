#pragma once
// What a saved map holds (and what a Mapper snapshot is): the pose graph, the keyframes with
// their descriptors, and the local maps. Localisation and map maintenance load the same data.
// Keyframes and local maps are shared and immutable, so a snapshot is cheap and can be saved
// from another thread while mapping goes on.
//
// Format versions: 1 (no localisation descriptors), 2 (each keyframe also holds a ScanContext++
// descriptor for global localisation) and 3 (format 2, and the manifest lists the sessions that
// built the map; the binary files are format 2's but for their version field). All three load. A
// map is saved in the oldest format that holds it exactly: 3 when it records sessions, else 2,
// and 1 without localisation descriptors (localisation_descriptor_config.rings == 0, e.g. a
// loaded format-1 map; its sessions are not recorded), so loading and saving a map of format 1 or
// 2 leaves its files unchanged.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/core/io_error.hpp"
#include "common/core/local_map_data.hpp"
#include "map/core/map_graph.hpp"
#include "places/core/scan_context.hpp"

namespace ltm::map {

// Formats 1 to 3 store a local map's voxels as rows; format 4 (map_format.hpp:
// kNewestMapFormatVersion, what a map that records sessions is saved as) stores them as compressed
// columns. What a build can read is map_format.hpp's readable_map_format.
constexpr std::uint32_t kRowMapFormatVersion = 3;  // the newest row format
constexpr std::uint32_t kOldestMapFormatVersion = 1;

// A damaged map file: what() is "file: field at byte N: problem" (one line).
using MapFormatError = common::FormatError;

struct StoredKeyframe {
    std::uint32_t session = 0;
    std::uint64_t node = 0;          // graph node of the local map it was registered in
    common::KeyframeData data;       // T_anchor_lidar is relative to that node; points may be empty
    places::ScanContext descriptor;  // loop closure (MapData::descriptor_config)
    // Global localisation (MapData::localisation_descriptor_config); empty in a format-1 map and
    // in the keyframes a format-1 map had when a later session continued it.
    places::ScanContext localisation_descriptor;
};

// A local map's file in a map directory, as a save wrote it (name relative to the directory).
struct LocalMapFile {
    std::uint64_t node = 0;
    std::uint32_t format = 0;  // the format version it was written in
    std::string file;
    std::uint64_t size = 0, hash = 0;  // bytes, FNV-1a 64 of them
};

struct StoredLocalMap {
    std::uint64_t node = 0;  // graph node (its anchor)
    std::uint32_t session = 0;
    std::shared_ptr<const common::LocalMapData> data;
    // Paged out (data == nullptr): the local map is this file of the directory being saved,
    // unchanged since a save wrote it; a save keeps the file (MapWriter::save).
    std::shared_ptr<const LocalMapFile> paged{};
};

// The localisation_descriptor_config of a map without localisation descriptors (format 1):
// kind kMeanVariance, rings = sectors = 0 (the range fields keep their defaults, unused).
inline places::ScanContextConfig no_localisation_descriptors() {
    places::ScanContextConfig c;
    c.kind = places::ScanContextKind::kMeanVariance;
    c.rings = 0;
    c.sectors = 0;
    return c;
}
inline bool has_localisation_descriptors(const places::ScanContextConfig& c) { return c.rings > 0; }

// A session that built the map (format 3: the manifest lists them).
struct SessionRecord {
    std::uint32_t id = 0;
    double first_stamp = 0.0, last_stamp = 0.0;  // of its keyframes [s]
    std::uint64_t local_maps_added = 0;          // new local maps (graph nodes)
    std::uint64_t local_maps_updated = 0;        // existing local maps it folded its own into
    std::string robot{};  // the robot that drove it ("" when one robot built the map)
};

struct MapData {
    std::uint64_t revision = 0;                   // increases with every optimisation of the graph
    places::ScanContextConfig descriptor_config;  // how the keyframe (loop) descriptors were made
    // How the keyframes' localisation descriptors were made (ScanContext++), or none (rings 0).
    places::ScanContextConfig localisation_descriptor_config = no_localisation_descriptors();
    std::vector<PoseGraphNode> nodes;  // node ids unique; each local map and keyframe names one
    std::vector<PoseGraphEdge> edges;
    std::vector<std::shared_ptr<const StoredKeyframe>> keyframes;  // in the order they came
    std::vector<StoredLocalMap> local_maps;                        // by node, ascending
    std::vector<SessionRecord> sessions;  // by id, ascending; empty in a format-1 or -2 map
};

}  // namespace ltm::map
