#pragma once
// What a saved map holds (and what a Mapper snapshot is): the pose graph, the keyframes with
// their descriptors, and the local maps. Localisation and map maintenance load the same data.
// Keyframes and local maps are shared and immutable, so a snapshot is cheap and can be saved
// from another thread while mapping goes on.
#include <cstdint>
#include <memory>
#include <vector>

#include "common/core/io_error.hpp"
#include "common/core/local_map_data.hpp"
#include "mapping/core/pose_graph.hpp"
#include "mapping/core/scan_context.hpp"

namespace ltm::mapping {

constexpr std::uint32_t kMapFormatVersion = 1;

// A damaged map file: what() is "file: field at byte N: problem" (one line).
using MapFormatError = common::FormatError;

struct StoredKeyframe {
    std::uint32_t session = 0;
    std::uint64_t node = 0;     // graph node of the local map it was registered in
    common::KeyframeData data;  // T_anchor_lidar is relative to that node; points may be empty
    ScanContext descriptor;
};

struct StoredLocalMap {
    std::uint64_t node = 0;  // graph node (its anchor)
    std::uint32_t session = 0;
    std::shared_ptr<const common::LocalMapData> data;
};

struct MapData {
    std::uint64_t revision = 0;           // increases with every optimisation of the graph
    ScanContextConfig descriptor_config;  // how the keyframe descriptors were made
    std::vector<PoseGraphNode> nodes;     // node ids unique; each local map and keyframe names one
    std::vector<PoseGraphEdge> edges;
    std::vector<std::shared_ptr<const StoredKeyframe>> keyframes;  // in the order they came
    std::vector<StoredLocalMap> local_maps;                        // by node, ascending
};

}  // namespace ltm::mapping
