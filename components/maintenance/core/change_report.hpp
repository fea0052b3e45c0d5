#pragma once
// The human side of a maintenance pass: a plain-text summary (one line for the pass, one a segment
// change) and a PLY of the voxels it changed, removed ones red and added ones green (binary
// little-endian: x y z float, red green blue uchar; every viewer colours it).
#include <ostream>
#include <string>
#include <vector>

#include "maintenance/core/change_set.hpp"

namespace ltm::maintenance {

// "session 0 pass 3: 2 moving, 1 vanished, 0 new segments; 412 of 90210 voxels removed, ..."
// then "  moving   id 17  centre ...". `pass` numbers the passes of a run.
void write_change_summary(std::ostream& out, const ChangeSet& changes, std::size_t pass);

// Written atomically; throws common::IoError.
void write_change_ply(const std::string& path, const ChangeSet& changes);
// The same for the changes of several passes, from their records (change_record.hpp), read one
// at a time: a run's changes need not stay in memory until its end (issue 28: they grew the
// robot's memory by the day's length). Throws what read_change_record and the write throw.
void write_change_ply(const std::string& path, const std::vector<std::string>& records);

}  // namespace ltm::maintenance
