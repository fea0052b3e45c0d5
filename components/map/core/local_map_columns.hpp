#pragma once
// A local map's voxels as compressed columns: the voxel section of a format-4 local-map file
// (map_codec.cpp; issue 26: the map on disk). Lossless, bit for bit: every float comes back with
// its bits, the voxels in their order.
//
//   u64 bytes of the columns, u64 count of every column (kColumns of them), then one zstd frame
//   (common/core/column_block.hpp) of the columns, each grouped by byte position. A column holds
//   what a prediction leaves: the index as the difference to the previous voxel's; the centre's
//   float bits minus those of its cell's middle; the normal's z bits minus those of
//   sqrt(1 - x^2 - y^2); created and last_seen as 1 + their index in the map's observation times
//   when they are one of them (else 0 and the double in a column of its own); the rest as stored.
// Reading checks what the row format (formats 1-3) checks, with the same field names.
#include <vector>

#include "common/core/byte_io.hpp"
#include "common/core/local_map_data.hpp"

namespace ltm::map {

void write_voxel_columns(common::ByteWriter& w, const common::LocalMapData& map);

// Reads map.voxels.size() voxels (the header's count) from the rest of s; the observation times
// and voxel size must be read already. Throws common::FormatError (one line).
void read_voxel_columns(common::ByteReader& s, common::LocalMapData& map);

}  // namespace ltm::map
