#include "map/core/map_store.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <sstream>
#include <unordered_set>

#include "common/core/file_io.hpp"
#include "common/core/io_error.hpp"
#include "map/core/map_codec.hpp"
#include "map/core/map_manifest.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

constexpr std::uint64_t kFirstHeaderField = 16;  // magic, version, section length

// FNV-1a 64 of a whole file: names files and checks them against the manifest. (A CRC-32 of a
// file made of CRC-protected sections would not do: a section's bytes and its own CRC change
// together in a way that leaves the CRC of the whole unchanged.)
std::uint64_t fnv1a64(const std::string& bytes) { return map_file_hash(bytes); }

std::string hex64(std::uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

std::string padded(std::uint64_t v, int width) {
    std::ostringstream s;
    s << std::setw(width) << std::setfill('0') << v;
    return s.str();
}

// The file's bytes, checked against the manifest after decoding (which locates damage better).
void check_entry(const ManifestEntry& e, const std::string& bytes) {
    if (bytes.size() != e.size) {
        throw MapFormatError(e.file, "size: " + std::to_string(bytes.size()) +
                                         " bytes, the manifest says " + std::to_string(e.size) +
                                         " (truncated or replaced)");
    }
    const std::uint64_t hash = fnv1a64(bytes);
    if (hash != e.hash) {
        throw MapFormatError(e.file, "file checksum: FNV-1a " + hex64(hash) +
                                         " differs from the manifest's " + hex64(e.hash));
    }
}

// A file of another format than the manifest's (a file copied from another map).
void check_version(const ManifestEntry& e, std::uint32_t version, std::uint32_t manifest) {
    if (version != manifest) {
        throw MapFormatError(e.file, "format version", 8,
                             "version " + std::to_string(version) + ", the manifest says " +
                                 std::to_string(manifest));
    }
}

}  // namespace

MapWriter::MapWriter(std::string dir, SaveOptions options)
    : dir_(std::move(dir)), options_(options) {
    if (options_.keyframes_per_file == 0) options_.keyframes_per_file = 1;
}

SaveStats MapWriter::save(const MapData& map, const std::function<void()>& between) {
    SaveStats stats;
    std::error_code ec;
    fs::create_directories(fs::path(dir_) / "local_maps", ec);
    if (ec) throw common::IoError(dir_, "cannot create the map directory: " + ec.message());

    const std::uint32_t version =
        map_format_for(map.localisation_descriptor_config, !map.sessions.empty());
    const DescriptorSettings settings{map.descriptor_config, map.localisation_descriptor_config};
    Manifest manifest;
    manifest.revision = map.revision;
    if (version >= 3) manifest.sessions = map.sessions;
    manifest.descriptor = map.descriptor_config;
    manifest.localisation_descriptor = map.localisation_descriptor_config;
    // Cache keys name the format too: a file of another format is not kept.
    const std::string v = "v" + std::to_string(version) + ":";
    std::unordered_map<std::string, Written> cache;
    // Writes (or keeps) one file; `key` names it in the cache.
    // The same content-named file of options_.link_from, hard-linked to `path`.
    auto link_file = [&](const std::string& file, std::uint64_t size, const fs::path& path) {
        if (options_.link_from.empty()) return false;
        const fs::path from = fs::path(options_.link_from) / file;
        std::error_code lec;
        if (!fs::is_regular_file(from, lec) || fs::file_size(from, lec) != size || lec)
            return false;
        fs::remove(path, lec);  // a leftover of another size
        fs::create_hard_link(from, path, lec);
        return !lec;
    };
    auto emit = [&](const std::string& key, const std::string& kind, const std::string& prefix,
                    const std::vector<std::shared_ptr<const void>>& from,
                    const std::function<std::string()>& encode) -> ManifestEntry {
        ManifestEntry e;
        e.kind = kind;
        const auto hit = cache_.find(key);
        const auto same = [&](const Written& w) {
            if (w.from.size() != from.size()) return false;
            for (std::size_t i = 0; i < from.size(); ++i)
                if (w.from[i].lock() != from[i]) return false;
            return true;
        };
        if (!from.empty() && hit != cache_.end() && same(hit->second) &&
            fs::file_size(fs::path(dir_) / hit->second.file, ec) == hit->second.size && !ec) {
            e.file = hit->second.file;
            e.size = hit->second.size;
            e.hash = hit->second.hash;
            ++stats.files_kept;
        } else {
            const std::string bytes = encode();
            e.hash = fnv1a64(bytes);
            e.size = bytes.size();
            e.file = prefix + hex64(e.hash) + ".bin";
            const fs::path path = fs::path(dir_) / e.file;
            if (fs::exists(path, ec) && fs::file_size(path, ec) == e.size) {
                ++stats.files_kept;  // the same content is already there (named by its CRC)
            } else if (link_file(e.file, e.size, path)) {
                ++stats.files_linked;
            } else {
                common::write_file_atomic(path.string(), bytes);
                ++stats.files_written;
                stats.bytes_written += bytes.size();
            }
            if (between) between();
        }
        stats.bytes_total += e.size;
        if (!from.empty()) cache[key] = Written{{from.begin(), from.end()}, e.file, e.size, e.hash};
        return e;
    };

    manifest.files.push_back(emit("graph", "graph", "graph_", {}, [&] {
        return encode_graph(map.revision, map.nodes, map.edges, version);
    }));
    const std::size_t per = options_.keyframes_per_file;
    for (std::size_t a = 0; a < map.keyframes.size(); a += per) {
        const std::size_t n = std::min(per, map.keyframes.size() - a);
        ManifestEntry e =
            emit(v + "kf:" + std::to_string(a) + ":" + std::to_string(n), "keyframes",
                 "keyframes_" + padded(a, 8) + "_",
                 {map.keyframes.begin() + std::ptrdiff_t(a),
                  map.keyframes.begin() + std::ptrdiff_t(a + n)},
                 [&] { return encode_keyframes(settings, map.keyframes, a, n, version); });
        e.first = a;
        e.count = n;
        manifest.files.push_back(e);
    }
    std::unordered_map<std::uint64_t, WrittenLocalMap> written_local_maps;
    for (const StoredLocalMap& m : map.local_maps) {
        if (!m.data && m.paged) {  // paged out: its file as a save wrote it
            // Named as written even when damaged since (a load refuses that one file, by name):
            // a save never drops a local map nor writes another over it.
            const LocalMapFile& f = *m.paged;
            if (f.format != version || f.node != m.node) {
                throw common::IoError(f.file, "the paged-out local map of node " +
                                                  std::to_string(m.node) + " is of format " +
                                                  std::to_string(f.format) + ", this save's is " +
                                                  std::to_string(version));
            }
            ManifestEntry e;
            e.kind = "local_map";
            e.file = f.file;
            e.size = f.size;
            e.hash = f.hash;
            e.node = m.node;
            ++stats.files_kept;
            stats.bytes_total += e.size;
            manifest.files.push_back(e);
            written_local_maps[m.node] = WrittenLocalMap{{}, m.paged};
            continue;
        }
        if (!m.data) continue;
        ManifestEntry e = emit(v + "lm:" + std::to_string(m.node), "local_map",
                               "local_maps/lm_" + padded(m.node, 8) + "_", {m.data},
                               [&] { return encode_local_map(m, version); });
        e.node = m.node;
        manifest.files.push_back(e);
        written_local_maps[m.node] =
            WrittenLocalMap{m.data, std::make_shared<const LocalMapFile>(
                                        LocalMapFile{m.node, version, e.file, e.size, e.hash})};
    }
    const std::string text = write_manifest(manifest);
    common::write_file_atomic((fs::path(dir_) / kManifestFile).string(), text);
    ++stats.files_written;
    stats.bytes_written += text.size();
    cache_.swap(cache);
    written_local_maps_.swap(written_local_maps);

    // Files of earlier saves that the new manifest does not name.
    std::unordered_set<std::string> keep;
    for (const ManifestEntry& e : manifest.files) keep.insert(e.file);
    for (const char* sub : {"", "local_maps"}) {
        const fs::path folder = fs::path(dir_) / sub;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
            if (!entry.is_regular_file()) continue;
            const std::string name = entry.path().filename().string();
            const std::string rel = std::string(sub).empty() ? name : std::string(sub) + "/" + name;
            const bool ours = name.rfind("graph_", 0) == 0 || name.rfind("keyframes_", 0) == 0 ||
                              name.rfind("lm_", 0) == 0;
            const bool bin = name.size() > 4 && (name.compare(name.size() - 4, 4, ".bin") == 0 ||
                                                 name.compare(name.size() - 4, 4, ".tmp") == 0);
            if (ours && bin && !keep.count(rel)) {
                fs::remove(entry.path(), ec);
                if (!ec) ++stats.files_removed;
            }
        }
    }
    return stats;
}

namespace {

// A local-map file's bytes checked against its manifest entry and the graph's nodes.
StoredLocalMap check_local_map(const ManifestEntry& e, const std::string& bytes,
                               std::uint32_t manifest_version,
                               const std::unordered_set<std::uint64_t>& nodes) {
    std::uint32_t version = 0;
    StoredLocalMap m = decode_local_map(bytes, e.file, &version);
    check_entry(e, bytes);
    check_version(e, version, manifest_version);
    if (m.node != e.node) {
        throw MapFormatError(
            e.file, "header.node", kFirstHeaderField,
            "node " + std::to_string(m.node) + ", the manifest says " + std::to_string(e.node));
    }
    if (!nodes.count(m.node)) {
        throw MapFormatError(e.file, "header.node", kFirstHeaderField,
                             "node " + std::to_string(m.node) + " is not in the graph");
    }
    return m;
}

}  // namespace

StoredLocalMap load_local_map(const std::string& dir, const ManifestEntry& entry,
                              std::uint32_t format_version,
                              const std::unordered_set<std::uint64_t>& nodes) {
    const std::string bytes = common::read_file((fs::path(dir) / entry.file).string(), entry.file);
    return check_local_map(entry, bytes, format_version, nodes);
}

StoredLocalMap load_local_map(const std::string& dir, const LocalMapFile& file) {
    const std::string bytes = common::read_file((fs::path(dir) / file.file).string(), file.file);
    ManifestEntry e;
    e.file = file.file;
    e.size = file.size;
    e.hash = file.hash;
    e.node = file.node;
    return check_local_map(e, bytes, file.format, {file.node});
}

SaveStats save_map(const std::string& dir, const MapData& map, const SaveOptions& options) {
    return MapWriter(dir, options).save(map);
}

LoadedMap load_map(const std::string& dir, bool with_local_maps) {
    LoadedMap out;
    out.format_version = 0;
    const fs::path root(dir);
    if (!fs::is_directory(root)) throw MapFormatError(dir, "not a directory");
    const Manifest manifest =
        parse_manifest(common::read_file((root / kManifestFile).string(), kManifestFile));
    MapData& map = out.map;
    map.descriptor_config = manifest.descriptor;
    map.localisation_descriptor_config = manifest.localisation_descriptor;
    map.sessions = manifest.sessions;
    out.format_version = manifest.version;
    const DescriptorSettings expected{manifest.descriptor, manifest.localisation_descriptor};

    // The graph first: without it nothing can be placed.
    for (const ManifestEntry& e : manifest.files) {
        if (e.kind != "graph") continue;
        const std::string bytes = common::read_file((root / e.file).string(), e.file);
        std::uint64_t revision = 0;
        std::uint32_t version = 0;
        decode_graph(bytes, e.file, &revision, &map.nodes, &map.edges, &version);
        check_entry(e, bytes);
        check_version(e, version, manifest.version);
        if (revision != manifest.revision) {
            throw MapFormatError(e.file, "header.revision", kFirstHeaderField,
                                 "revision " + std::to_string(revision) + ", the manifest says " +
                                     std::to_string(manifest.revision));
        }
        map.revision = revision;
    }
    std::unordered_set<std::uint64_t> nodes;
    for (const PoseGraphNode& n : map.nodes) nodes.insert(n.id);

    for (const ManifestEntry& e : manifest.files) {
        if (e.kind == "graph") continue;
        if (e.kind != "keyframes" && !with_local_maps) {  // left on disk (load_local_map)
            out.local_map_files.push_back(e);
            continue;
        }
        try {
            const std::string bytes = common::read_file((root / e.file).string(), e.file);
            if (e.kind == "keyframes") {
                std::uint64_t first = 0;
                std::uint32_t version = 0;
                auto keyframes = decode_keyframes(bytes, e.file, &expected, &first, &version);
                check_entry(e, bytes);
                check_version(e, version, manifest.version);
                if (first != e.first || keyframes.size() != e.count) {
                    throw MapFormatError(e.file, "header.first", kFirstHeaderField,
                                         "holds keyframes " + std::to_string(first) + "+" +
                                             std::to_string(keyframes.size()) +
                                             ", the manifest says " + std::to_string(e.first) +
                                             "+" + std::to_string(e.count));
                }
                for (std::size_t i = 0; i < keyframes.size(); ++i) {
                    if (!nodes.count(keyframes[i]->node)) {
                        throw MapFormatError(e.file, "keyframes[" + std::to_string(first + i) +
                                                         "].node: node " +
                                                         std::to_string(keyframes[i]->node) +
                                                         " is not in the graph");
                    }
                }
                map.keyframes.insert(map.keyframes.end(), keyframes.begin(), keyframes.end());
            } else {
                StoredLocalMap m = check_local_map(e, bytes, manifest.version, nodes);
                map.local_maps.push_back(std::move(m));
            }
        } catch (const common::IoError& error) {  // unreadable or damaged (MapFormatError)
            out.refused.push_back(error.what());
        }
    }
    std::sort(map.local_maps.begin(), map.local_maps.end(),
              [](const StoredLocalMap& a, const StoredLocalMap& b) { return a.node < b.node; });
    return out;
}

}  // namespace ltm::map
