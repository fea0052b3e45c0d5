#pragma once
// Format 4 of a saved map (issue 26: compact files). map_data.hpp names formats 1 to 3; format 4
// is format 3 with a local map's voxels as compressed columns (local_map_columns.hpp) and a
// keyframe file's keyframe sections in one zstd frame; the manifest and the graph are format 3's.
// A map that records sessions (every Mapper snapshot) is saved as format 4 (map_format_for).
// Kept apart from map_data.hpp so that the many files including that one need no rebuild; "newest"
// is kNewestMapFormatVersion here (map_data.hpp's kRowMapFormatVersion is the newest row format).
#include <cstdint>
#include <string>

#include "map/core/map_data.hpp"

namespace ltm::map {

constexpr std::uint32_t kCompactMapFormatVersion = 4;
constexpr std::uint32_t kNewestMapFormatVersion = kCompactMapFormatVersion;

inline bool readable_map_format(std::uint32_t version) {
    return version >= kOldestMapFormatVersion && version <= kNewestMapFormatVersion;
}
// "format version 5 is not supported (this build reads versions 1 to 4)"
inline std::string unreadable_map_format(std::uint32_t version) {
    return "format version " + std::to_string(version) +
           " is not supported (this build reads versions " +
           std::to_string(kOldestMapFormatVersion) + " to " +
           std::to_string(kNewestMapFormatVersion) + ")";
}

}  // namespace ltm::map
