#pragma once
// The human side of a maintenance pass: a plain-text summary (one line for the pass, one a segment
// change) and a PLY of the voxels it changed, removed ones red and added ones green (binary
// little-endian: x y z float, red green blue uchar; every viewer colours it).
#include <ostream>
#include <string>

#include "maintenance/core/change_set.hpp"

namespace ltm::maintenance {

// "session 0 pass 3: 2 moving, 1 vanished, 0 new segments; 412 of 90210 voxels removed, ..."
// then "  moving   id 17  centre ...". `pass` numbers the passes of a run.
void write_change_summary(std::ostream& out, const ChangeSet& changes, std::size_t pass);

// Written atomically; throws common::IoError.
void write_change_ply(const std::string& path, const ChangeSet& changes);

}  // namespace ltm::maintenance
