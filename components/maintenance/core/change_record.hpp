#pragma once
// A ChangeSet as a file (a change record): little-endian, the magic "LTM-CHNG", a format version
// and checksummed sections (common/core/byte_io.hpp): a header (session, map time, voxel size,
// the pass's figures, the number of changes), then one section per segment change (id, reason,
// region, centroid, box, first and last seen, score, judged voxels, voxel centres). Written once
// and read back exactly (every float bit for bit).
//
// Reading checks every field: a damaged, truncated or foreign file, or one of another version,
// throws common::FormatError, one line naming the file, the field and its byte offset
// ("changes_0003.ltmc: changes[2] at byte 181: checksum mismatch ..."); nothing is returned.
#include <cstdint>
#include <string>

#include "maintenance/core/change_set.hpp"

namespace ltm::maintenance {

constexpr std::uint32_t kChangeRecordVersion = 1;

// The bytes of a change record.
std::string encode_change_record(const ChangeSet& changes);
// `source` names the bytes in errors (a file name). Throws common::FormatError.
ChangeSet decode_change_record(const std::string& bytes, const std::string& source);

// Written atomically (a reader never sees half a record); throws common::IoError.
void write_change_record(const std::string& path, const ChangeSet& changes);
// Throws common::IoError (unreadable) or common::FormatError (damaged).
ChangeSet read_change_record(const std::string& path);

}  // namespace ltm::maintenance
