#pragma once
// Is a saved map whole? The cheap checks a site runs on its versions before a session starts on
// one (site_store.hpp): no voxel is decoded, every byte is read once.
//   - a map directory: its manifest parses (map_manifest.hpp) and every file it names is there
//     with the manifest's size and FNV-1a 64 hash;
//   - a maintained map (maintenance/core/long_term_map.hpp, "LTMMAINT"): its signature, then
//     sections (u32 length, bytes, u32 CRC-32) up to the end of the file, each CRC right. The
//     format version is not judged here (the maintenance core does that when it loads the file),
//     so the check holds for every version whose body is CRC-framed sections.
#include <string>

namespace ltm::map {

// "" when whole, else one line naming the file and the problem
// ("local_maps/lm_00000003_....bin: 1200 bytes, the manifest says 5316 (truncated or replaced)").
std::string check_map_dir(const std::string& dir);

// "" when whole (or `path` does not exist and `must_exist` is false), else one line.
std::string check_maintained_map_file(const std::string& path, bool must_exist = false);

}  // namespace ltm::map
