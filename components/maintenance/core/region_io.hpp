#pragma once
// One region of the maintained map as a checksummed section (long_term_map_io.cpp): the format of
// a region in the map file, and of a region paged out to disk (region_pager.hpp).
//   section: int32 x, int32 y, uint32 voxels, then the voxels (key, point sums, times, flags,
//   view history) as compressed columns (format version 3, region_columns.hpp); version 2 had
//   each voxel as in memory, one after another.
#include <cstdint>
#include <utility>

#include "common/core/byte_io.hpp"
#include "maintenance/core/observation_map.hpp"

namespace ltm::maintenance {

constexpr std::uint32_t kMaintainedMapVersion = 3;   // the file format written
constexpr std::uint32_t kMaintainedMapVersion2 = 2;  // still read (voxels as rows)
constexpr std::uint32_t kMaintainedMapVersion1 = 1;  // still read, converted

// Appends the region's section to w.
void write_region_section(common::ByteWriter& w, const std::pair<int, int>& key,
                          const ObservationMap& map);

// Reads one region section (of a file of `version`) from r: its key first, then its voxels into
// the map `map_for(key)` returns (ObservationMap&). Throws common::FormatError on damage.
template <class MapFor>
void read_region_section(common::ByteReader& r, std::uint32_t version, float voxel_size,
                         MapFor&& map_for);

namespace detail {
std::pair<int, int> read_region_key(common::ByteReader& s);
void read_region_voxels(common::ByteReader& s, std::uint32_t version, float voxel_size,
                        ObservationMap& map);
}  // namespace detail

template <class MapFor>
void read_region_section(common::ByteReader& r, std::uint32_t version, float voxel_size,
                         MapFor&& map_for) {
    r.section("region", [&](common::ByteReader& s) {
        const std::pair<int, int> key = detail::read_region_key(s);
        detail::read_region_voxels(s, version, voxel_size, map_for(key));
    });
}

}  // namespace ltm::maintenance
