#pragma once
// What a saved map holds (and what a Mapper snapshot is): the pose graph, the keyframes with
// their descriptors, and the local maps. Localisation and map maintenance load the same data.
// Keyframes and local maps are shared and immutable, so a snapshot is cheap and can be saved
// from another thread while mapping goes on.
//
// Format versions: 1 (no localisation descriptors) and 2 (each keyframe also holds a ScanContext++
// descriptor for global localisation). Both load. A map is saved in format 2, except a map without
// localisation descriptors (localisation_descriptor_config.rings == 0, e.g. a loaded format-1
// map): format 1 holds it exactly, so loading and saving such a map leaves its files unchanged.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/core/io_error.hpp"
#include "common/core/local_map_data.hpp"
#include "mapping/core/pose_graph.hpp"
#include "mapping/core/scan_context.hpp"

namespace ltm::mapping {

constexpr std::uint32_t kMapFormatVersion = 2;  // the newest: what a map with every part takes
constexpr std::uint32_t kOldestMapFormatVersion = 1;

inline bool supported_map_format(std::uint32_t version) {
    return version >= kOldestMapFormatVersion && version <= kMapFormatVersion;
}
// "format version 3 is not supported (this build reads versions 1 and 2)"
inline std::string unsupported_map_format(std::uint32_t version) {
    return "format version " + std::to_string(version) +
           " is not supported (this build reads versions " +
           std::to_string(kOldestMapFormatVersion) + " and " + std::to_string(kMapFormatVersion) +
           ")";
}

// A damaged map file: what() is "file: field at byte N: problem" (one line).
using MapFormatError = common::FormatError;

struct StoredKeyframe {
    std::uint32_t session = 0;
    std::uint64_t node = 0;     // graph node of the local map it was registered in
    common::KeyframeData data;  // T_anchor_lidar is relative to that node; points may be empty
    ScanContext descriptor;     // loop closure (MapData::descriptor_config)
    // Global localisation (MapData::localisation_descriptor_config); empty in a format-1 map and
    // in the keyframes a format-1 map had when a later session continued it.
    ScanContext localisation_descriptor;
};

struct StoredLocalMap {
    std::uint64_t node = 0;  // graph node (its anchor)
    std::uint32_t session = 0;
    std::shared_ptr<const common::LocalMapData> data;
};

// The localisation_descriptor_config of a map without localisation descriptors (format 1):
// kind kMeanVariance, rings = sectors = 0 (the range fields keep their defaults, unused).
inline ScanContextConfig no_localisation_descriptors() {
    ScanContextConfig c;
    c.kind = ScanContextKind::kMeanVariance;
    c.rings = 0;
    c.sectors = 0;
    return c;
}
inline bool has_localisation_descriptors(const ScanContextConfig& c) { return c.rings > 0; }

struct MapData {
    std::uint64_t revision = 0;           // increases with every optimisation of the graph
    ScanContextConfig descriptor_config;  // how the keyframe (loop) descriptors were made
    // How the keyframes' localisation descriptors were made (ScanContext++), or none (rings 0).
    ScanContextConfig localisation_descriptor_config = no_localisation_descriptors();
    std::vector<PoseGraphNode> nodes;  // node ids unique; each local map and keyframe names one
    std::vector<PoseGraphEdge> edges;
    std::vector<std::shared_ptr<const StoredKeyframe>> keyframes;  // in the order they came
    std::vector<StoredLocalMap> local_maps;                        // by node, ascending
};

}  // namespace ltm::mapping
