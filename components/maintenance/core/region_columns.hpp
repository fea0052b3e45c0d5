#pragma once
// A region's voxels as compressed columns: the body of a region section in maintained-map format
// version 3 (region_io.hpp; issue 26: the maintained state on disk). Lossless: the voxels come
// back exactly as they were, in the same order (the decisions cannot change).
//
//   u64 count of every column (kRegionColumns of them), u64 bytes of the columns, then one zstd
//   frame (common/core/column_block.hpp) of the columns, each grouped by byte position:
//     key (difference to the previous voxel's, uint64 wrapping), point count, sums (3 int16),
//     squared sums (6 int16), created (difference to the previous voxel's, ticks), last point
//     (minus created), flags, first hit (difference to the previous voxel's), hit span, entries;
//     each entry's slot minus the voxel's first hit, hits, free.
// What the columns hold is checked as the row format (version 2) checks it; damage is one line.
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/byte_io.hpp"
#include "maintenance/core/observation_map.hpp"

namespace ltm::maintenance {

// Appends the columns of `map`'s voxels to w.
void write_region_columns(common::ByteWriter& w, const ObservationMap& map);

// Reads `voxels` voxels from the rest of s (a region section after its key and voxel count) into
// `map`. Throws common::FormatError (source s's).
void read_region_columns(common::ByteReader& s, std::uint32_t voxels, ObservationMap& map);

}  // namespace ltm::maintenance
