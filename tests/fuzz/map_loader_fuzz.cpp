// Fuzz target: loading a saved map (mapping/core: map_store, map_codec). The first byte picks the
// kind of file the rest is:
//   0 a local map, 1 the pose graph, 2 a keyframe file (each decoded from memory), 3 manifest.txt
//   of a map folder that otherwise holds the files of mapping/core/testdata/map_v1 (load_map).
// Promise: the decoded content, or a one-line MapFormatError (or IoError, when a file the manifest
// names cannot be read); a refused local-map or keyframe file of a folder is a one-line entry of
// LoadedMap::refused. What decodes re-encodes to bytes that
// decode and encode to the same bytes again (one description for both directions).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "common/core/io_error.hpp"
#include "fuzz_util.hpp"
#include "map/core/map_codec.hpp"
#include "map/core/map_store.hpp"

namespace fs = std::filesystem;

namespace {

// The map folder of kind 3: the fixture's files, the manifest replaced each run.
const std::string& map_dir() {
    static const std::string dir = [] {
        const std::string d = ltm::fuzz::scratch_dir() + "/map";
        fs::copy(LTM_SOURCE_DIR "/components/map/core/testdata/map_v1", d,
                 fs::copy_options::recursive | fs::copy_options::overwrite_existing);
        return d;
    }();
    return dir;
}

void same_again(const std::string& first, const std::string& second, const char* what) {
    if (first != second)
        ltm::fuzz::finding(std::string(what) + ": encode(decode(bytes)) changes the bytes");
}

void local_map(const std::string& bytes) {
    const std::string once =
        ltm::map::encode_local_map(ltm::map::decode_local_map(bytes, "lm.bin"));
    same_again(once, ltm::map::encode_local_map(ltm::map::decode_local_map(once, "again.bin")),
               "local map");
}

void graph(const std::string& bytes) {
    std::uint64_t revision = 0;
    std::vector<ltm::map::PoseGraphNode> nodes;
    std::vector<ltm::map::PoseGraphEdge> edges;
    ltm::map::decode_graph(bytes, "graph.bin", &revision, &nodes, &edges);
    const std::string once = ltm::map::encode_graph(revision, nodes, edges);
    nodes.clear();
    edges.clear();
    ltm::map::decode_graph(once, "again.bin", &revision, &nodes, &edges);
    same_again(once, ltm::map::encode_graph(revision, nodes, edges), "graph");
}

void keyframes(const std::string& bytes) {
    std::uint64_t first = 0;
    // With the file's own descriptor settings (format 1 or 2), then the round trip.
    ltm::map::DescriptorSettings settings;
    const auto kfs =
        ltm::map::decode_keyframes(bytes, "keyframes.bin", nullptr, &first, nullptr, &settings);
    // Again checked against the fixture's descriptor settings (manifest.txt of map_v1).
    ltm::map::DescriptorSettings fixture;
    fixture.loop.kind = ltm::places::ScanContextKind::kMeanVariance;
    fixture.loop.rings = 6;
    fixture.loop.sectors = 12;
    fixture.loop.max_range = 60;
    fixture.loop.min_range = 0;
    fixture.loop.sensor_height = 1.73;
    try {
        ltm::map::decode_keyframes(bytes, "keyframes.bin", &fixture, &first);
    } catch (const ltm::common::IoError& e) {
        ltm::fuzz::expect_one_line(e);
    }
    const std::string once = ltm::map::encode_keyframes(settings, kfs, 0, kfs.size());
    const auto again = ltm::map::decode_keyframes(once, "again.bin", &settings, &first);
    same_again(once, ltm::map::encode_keyframes(settings, again, 0, again.size()), "keyframes");
}

void folder(const std::uint8_t* data, std::size_t size) {
    const std::string dir = map_dir();
    ltm::fuzz::write_input(data, size, "map/manifest.txt");
    const ltm::map::LoadedMap loaded = ltm::map::load_map(dir);
    for (const auto& r : loaded.refused)
        if (r.empty() || r.find_first_of("\n\r") != std::string::npos)
            ltm::fuzz::finding("a refusal that is not one line: '" + r + "'");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        switch (data[0] % 4) {
            case 0:
                local_map(bytes);
                break;
            case 1:
                graph(bytes);
                break;
            case 2:
                keyframes(bytes);
                break;
            default:
                folder(data + 1, size - 1);
                break;
        }
    } catch (const ltm::common::IoError& e) {  // MapFormatError is one
        ltm::fuzz::expect_one_line(e);
    }
    return 0;
}
