#pragma once
// A map directory (format 3, 2 or 1: map_data.hpp):
//   manifest.txt                       what the map is made of: every file with its size and
//                                      FNV-1a 64 hash, the revision and the descriptor settings
//                                      and the sessions that built the map (map_manifest.hpp)
//   graph_<hash>.bin                   the pose graph
//   keyframes_<first>_<hash>.bin       keyframes with their descriptors, in chunks
//   local_maps/lm_<node>_<hash>.bin    one file a local map (voxels with their life records)
// Inside each binary file, every section carries its own CRC-32 (map_codec.hpp).
// Files are named by their content, written atomically (temporary file, fsync, rename), and the
// manifest goes last: a crash during a save leaves the previous map intact. Files the new
// manifest does not name are removed afterwards. Unchanged local maps are not written again.
//
// Loading validates everything; formats 1 to 3 load (every file of the format the manifest
// names), any other version fails with one line naming the file, the version and the supported
// ones. A damaged manifest or graph fails the load (nothing could be placed); a damaged local-map
// or keyframe file is refused, named with the field and the byte offset of the damage, and the
// rest of the map loads.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "map/core/map_data.hpp"
#include "map/core/map_manifest.hpp"

namespace ltm::map {

struct SaveOptions {
    std::size_t keyframes_per_file = 1024;
    // Another map directory (the version a session started from, site_store.hpp): a file this
    // save would write that is there under the same content name and size is hard-linked from
    // it instead (no copy of unchanged local maps); writing is the fallback when linking fails
    // (another filesystem, no hard links). "": always write.
    std::string link_from{};
};

struct SaveStats {
    std::size_t files_written = 0, files_kept = 0, files_removed = 0;
    std::size_t files_linked = 0;  // hard-linked from SaveOptions::link_from (not written)
    std::uint64_t bytes_written = 0;
    std::uint64_t bytes_total = 0;  // of every file the manifest names
};

// Saves maps into one directory; remembers what it wrote so that unchanged local maps and full
// keyframe chunks are neither encoded nor written again.
class MapWriter {
  public:
    explicit MapWriter(std::string dir, SaveOptions options = {});
    // Throws common::IoError (naming the file) when a file cannot be written. `between` (when
    // given) is called after each file encoded, before the next: a caller that paces its CPU
    // waits there (the pieces of a save are single files; the manifest is written last).
    // A paged-out local map (StoredLocalMap::paged, no data) keeps its file as written (the
    // manifest names it; a save never leaves a local map out); IoError when it is of another
    // format than this save's.
    SaveStats save(const MapData& map, const std::function<void()>& between = {});
    const std::string& dir() const { return dir_; }

    // What the last save wrote or kept of each local map (by node), with the data it was made
    // from (expired when that data is gone; empty for a paged-out map kept as it was).
    struct WrittenLocalMap {
        std::weak_ptr<const common::LocalMapData> data;
        std::shared_ptr<const LocalMapFile> file;
    };
    const std::unordered_map<std::uint64_t, WrittenLocalMap>& written_local_maps() const {
        return written_local_maps_;
    }

  private:
    struct Written {
        // The objects the file was made from, every one: a folded local map's keyframes are
        // replaced in the middle of a chunk (new node), its first and last unchanged.
        std::vector<std::weak_ptr<const void>> from;
        std::string file;
        std::uint64_t size = 0;
        std::uint64_t hash = 0;
    };
    std::string dir_;
    SaveOptions options_;
    std::unordered_map<std::string, Written> cache_;
    std::unordered_map<std::uint64_t, WrittenLocalMap> written_local_maps_;
};

// One-off save.
SaveStats save_map(const std::string& dir, const MapData& map, const SaveOptions& options = {});

struct LoadedMap {
    MapData map;
    // One line a refused file: "local_maps/lm_...bin: voxels[17].normal at byte 1290: ...".
    std::vector<std::string> refused;
    // load_map(dir, false): the local-map files the manifest names, not read (map.local_maps
    // empty); load_local_map reads one of them.
    std::vector<ManifestEntry> local_map_files;
    std::uint32_t format_version = 0;  // the manifest's
};

// Throws MapFormatError when the manifest or the graph is damaged or of an unknown format version,
// common::IoError when one of them cannot be read. A format-1 map loads with empty localisation
// descriptors and localisation_descriptor_config == no_localisation_descriptors().
// with_local_maps false: the graph, keyframes and manifest only; the local maps stay on disk
// (listed in local_map_files, unchecked until read).
LoadedMap load_map(const std::string& dir, bool with_local_maps = true);

// One local-map file of a map directory (an entry of LoadedMap::local_map_files), checked as
// load_map checks it (size, hash, format version, node in `nodes`, the graph's). Throws
// common::IoError / MapFormatError with one line naming the file.
StoredLocalMap load_local_map(const std::string& dir, const ManifestEntry& entry,
                              std::uint32_t format_version,
                              const std::unordered_set<std::uint64_t>& nodes);

// One local map file of a map directory, checked as load_map checks it (size, checksum, format
// version, node). Throws MapFormatError (damaged) or common::IoError (unreadable), one line.
StoredLocalMap load_local_map(const std::string& dir, const LocalMapFile& file);

}  // namespace ltm::map
