#pragma once
// What a session changed in a site's map (site_store.hpp), measured from the map it started from
// and the one it saved, and kept beside the version as version.txt:
//   ltm_site_version 1
//   number 4                      created 1795810503 (UTC seconds)
//   started_from v0003            ("-" for a site's first version)
//   session 3                     the newest session the map records
//   sessions_added 3:robot1 4:robot2   the sessions this version adds, with the robot that drove
//                                 each ("-": one robot built the map); absent when none recorded
//   local_maps 48 / local_maps_added 3 / local_maps_updated 5 / local_maps_removed 0
//   keyframes 1210 / keyframes_added 120 / trajectory_m 512.3
//   voxels_removed 1234 / voxels_added 456       (by maintenance; absent when not known)
//   keyframes_compared 1090 / shift_max_m 0.012 / shift_mean_m 0.004 / turn_max_deg 0.10 /
//   turn_mean_deg 0.02            how far the start version's keyframes moved in the new map
// one `key value` a line. Reading ignores keys it does not know (a newer build's) and refuses a
// line it cannot parse.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ltm::map {

struct VersionSummary {
    std::uint32_t number = 0;   // set by SiteStore::commit
    std::int64_t created = 0;   // wall time [s since 1970, UTC]; commit sets it when 0
    std::string started_from;   // "v0003"; "" for the site's first version
    std::uint32_t session = 0;  // the newest session of the map
    // The sessions in the new map and not in the start one, each with its robot ("" for a map one
    // robot built): several robots changing one site on one day end in one version.
    std::vector<std::pair<std::uint32_t, std::string>> sessions_added;
    std::uint64_t local_maps = 0, local_maps_added = 0, local_maps_updated = 0;
    std::uint64_t local_maps_removed = 0;
    std::uint64_t keyframes = 0, keyframes_added = 0;
    double trajectory_m = 0.0;  // path of the keyframes added, session by session [m]
    std::optional<std::uint64_t> voxels_removed, voxels_added;  // by maintenance, when known
    // Keyframes of the start version also in the new map (same session, id and stamp): how far
    // their map-frame poses moved (the map frame stays put: inspection points keep coordinates).
    std::uint64_t keyframes_compared = 0;
    double shift_max_m = 0.0, shift_mean_m = 0.0;
    double turn_max_deg = 0.0, turn_mean_deg = 0.0;
};

// Measures what the map in `new_map_dir` changed against the one in `start_map_dir` ("": a new
// site). Reads manifests, graphs and keyframes, not the voxels. Throws common::IoError (one line)
// when either cannot be read.
VersionSummary measure_version(const std::string& new_map_dir, const std::string& start_map_dir,
                               const std::string& start_name);

std::string write_version_text(const VersionSummary& summary);
// Throws common::FormatError naming `name` and the line.
VersionSummary parse_version_text(const std::string& text, const std::string& name);

// "2026-11-27 20:15 UTC" of `created`.
std::string version_date(std::int64_t created);
// "3 local maps added, 5 updated; 120 keyframes (512 m); old keyframes moved max 0.012 m /
// 0.10 deg (mean 0.004 m); maintenance: 1234 voxels removed, 456 added; from v0003".
std::string version_line(const VersionSummary& summary);

}  // namespace ltm::map
