// Format-2 map files still load: testdata/map_v2 was written by the format-2 MapWriter of commit
// 9cec5e7 (the first with localisation descriptors) from fixture_map() below, with two keyframes a
// file: the format-1 fixture (testdata/map_v1) with ScanContext++ localisation descriptors of 5
// rings x 16 sectors on keyframes 0 and 2 (keyframe 1 has none, as a keyframe of a continued
// format-1 map). Loading it must give fixture_map() back, bit for bit, and saving what was loaded
// must give the same bytes again.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "map/core/map_store.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

const fs::path kTestData = fs::path(LTM_SOURCE_DIR) / "components/map/core/testdata";

// Deterministic numbers without <random> (its distributions are not portable): [0, 1).
float unit(std::uint32_t k) { return float((k * 2654435761u) >> 8) / float(1u << 24); }

MapData fixture_map() {
    const LoadedMap v1 = load_map((kTestData / "map_v1").string());
    EXPECT_TRUE(v1.refused.empty());
    MapData map = v1.map;
    places::ScanContextConfig& c = map.localisation_descriptor_config;
    c.kind = places::ScanContextKind::kMeanVariance;
    c.rings = 5;
    c.sectors = 16;
    c.max_range = 40.0;
    c.min_range = 0.5;
    c.sensor_height = 1.25;
    for (std::uint32_t i = 0; i < map.keyframes.size(); ++i) {
        if (i == 1) continue;
        auto k = std::make_shared<StoredKeyframe>(*map.keyframes[i]);
        places::ScanContext& sc = k->localisation_descriptor;
        sc.kind = c.kind;
        sc.rings = c.rings;
        sc.sectors = c.sectors;
        for (std::uint32_t b = 0; b < 80; ++b) {
            const bool occupied = (b + 2 * i) % 4 != 0;
            sc.value.push_back(occupied ? 6.0f * unit(300 * i + b) - 2.0f : 0.0f);
            sc.spread.push_back(occupied ? unit(300 * i + b + 90) : 0.0f);
            sc.occupied.push_back(occupied ? 1 : 0);
        }
        map.keyframes[i] = k;
    }
    return map;
}

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(MapFilesV2, LoadAsTheMapTheyWereWrittenFrom) {
    const LoadedMap loaded = load_map((kTestData / "map_v2").string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    const MapData expected = fixture_map();
    const MapData& map = loaded.map;
    EXPECT_EQ(map.revision, expected.revision);
    const places::ScanContextConfig &c = map.localisation_descriptor_config,
                                    &e = expected.localisation_descriptor_config;
    EXPECT_EQ(c.kind, e.kind);
    EXPECT_EQ(c.rings, e.rings);
    EXPECT_EQ(c.sectors, e.sectors);
    EXPECT_EQ(c.max_range, e.max_range);
    EXPECT_EQ(c.min_range, e.min_range);
    EXPECT_EQ(c.sensor_height, e.sensor_height);
    EXPECT_EQ(map.descriptor_config.rings, expected.descriptor_config.rings);
    EXPECT_EQ(map.nodes.size(), expected.nodes.size());
    EXPECT_EQ(map.edges.size(), expected.edges.size());
    EXPECT_EQ(map.local_maps.size(), expected.local_maps.size());
    ASSERT_EQ(map.keyframes.size(), expected.keyframes.size());
    for (std::size_t i = 0; i < map.keyframes.size(); ++i) {
        const StoredKeyframe &a = *map.keyframes[i], &b = *expected.keyframes[i];
        EXPECT_EQ(a.data.id, b.data.id);
        EXPECT_TRUE(a.data.T_anchor_lidar.isApprox(b.data.T_anchor_lidar, 0.0));
        EXPECT_EQ(a.data.points, b.data.points);
        EXPECT_TRUE(same_bits(a.descriptor.value, b.descriptor.value)) << i;
        const places::ScanContext &u = a.localisation_descriptor, &v = b.localisation_descriptor;
        EXPECT_EQ(u.empty(), i == 1) << i;
        EXPECT_EQ(u.kind, v.kind) << i;
        EXPECT_EQ(u.rings, v.rings) << i;
        EXPECT_EQ(u.sectors, v.sectors) << i;
        EXPECT_TRUE(same_bits(u.value, v.value)) << i;
        EXPECT_TRUE(same_bits(u.spread, v.spread)) << i;
        EXPECT_EQ(u.occupied, v.occupied) << i;
    }
}

TEST(MapFilesV2, SavedAgainGiveTheSameBytes) {
    const fs::path fixture = kTestData / "map_v2";
    const LoadedMap loaded = load_map(fixture.string());
    const fs::path again = fs::path(LTM_BINARY_DIR) / "map_test_maps" / "map_v2_again";
    fs::remove_all(again);
    SaveOptions options;
    options.keyframes_per_file = 2;
    save_map(again.string(), loaded.map, options);
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(fixture)) {
        if (!e.is_regular_file()) continue;
        const fs::path other = again / fs::relative(e.path(), fixture);
        ASSERT_TRUE(fs::exists(other)) << other;
        EXPECT_TRUE(file_bytes(e.path()) == file_bytes(other)) << other;
        ++files;
    }
    EXPECT_EQ(files, 1u + 1u + 2u + 3u);  // manifest, graph, two keyframe files, three local maps
}

}  // namespace
}  // namespace ltm::map
