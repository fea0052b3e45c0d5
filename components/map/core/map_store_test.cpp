// The map directory round trip, incremental saves, damage and versions (549 lines: one fixture
// map shared by every case; the format-1 and format-2 fixture files have their own tests).
#include "map/core/map_store.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/core/crc32.hpp"
#include "common/core/file_io.hpp"
#include "map/core/map_codec.hpp"
#include "map/core/map_manifest.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
    const fs::path p = fs::path(LTM_BINARY_DIR) / "map_test_maps" / name;
    fs::remove_all(p);
    return p;
}

std::shared_ptr<const common::LocalMapData> random_local_map(std::uint64_t id, std::uint32_t seed,
                                                             std::size_t voxels) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto m = std::make_shared<common::LocalMapData>();
    m->id = id;
    m->revision = seed % 7;
    m->finished = seed % 2 == 0;
    m->T_odom_anchor = registration::test::xy_yaw(10.0 * id, 3.0, 17.0 * id);
    m->T_anchor_grid = registration::test::xy_yaw(-0.3, 0.2, -17.0 * id);
    m->bbox_min = Eigen::Vector3d(-50, -50, -50);
    m->bbox_max = Eigen::Vector3d(50, 50, 50);
    m->voxel_size = 0.5f;
    for (int i = 0; i < 20; ++i) m->observation_times.push_back(100.0 + 0.1 * i);
    for (std::size_t i = 0; i < voxels; ++i) {
        common::VoxelData v;
        v.index = Eigen::Vector3i(int(i % 50) - 25, int(i / 50) - 10, int(i % 7) - 3);
        v.centre = (v.index.cast<float>() + Eigen::Vector3f(u(rng), u(rng), u(rng))) * 0.5f;
        v.normal = i % 5 == 0 ? Eigen::Vector3f::Zero()
                              : Eigen::Vector3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng)).normalized();
        v.point_count = std::uint32_t(1 + i % 60);
        v.planarity = u(rng);
        v.stability = u(rng);
        v.life.created = 100.0 + u(rng);
        v.life.last_seen = v.life.created + 0.5;
        v.life.observations = std::uint32_t(i % 13);
        v.life.health = u(rng);
        for (std::uint16_t k = 0; k < i % 4; ++k)
            v.life.seen.push_back(std::uint16_t((k * 7 + i) % 20));
        m->voxels.push_back(v);
    }
    return m;
}

MapData sample_map() {
    MapData map;
    map.revision = 5;
    map.descriptor_config.kind =
        places::ScanContextKind::kMeanVariance;  // both descriptor kinds load
    map.descriptor_config.rings = 10;
    map.descriptor_config.sectors = 24;
    map.localisation_descriptor_config.kind = places::ScanContextKind::kMeanVariance;
    map.localisation_descriptor_config.rings = 8;
    map.localisation_descriptor_config.sectors = 30;
    for (std::uint64_t n = 0; n < 3; ++n) {
        PoseGraphNode node;
        node.id = 10 + n;
        node.local_map_id = n;
        node.session = n == 2 ? 1 : 0;
        node.T_odom_anchor = registration::test::xy_yaw(10.0 * n, 0, 5.0 * n);
        node.T_world_anchor = registration::test::xy_yaw(10.0 * n + 0.1, 0.2, 5.0 * n + 1.0);
        node.fixed = n == 0;
        map.nodes.push_back(node);
        map.local_maps.push_back(
            {node.id, node.session, random_local_map(n, 7 + n, 3000 + 2000 * n)});
    }
    PoseGraphEdge e;
    e.from = 10;
    e.to = 11;
    e.T_from_to = registration::test::xy_yaw(10, 0, 5);
    e.information = Matrix6d::Identity() * 100.0;
    e.information(0, 1) = e.information(1, 0) = 3.0;
    map.edges.push_back(e);
    e.from = 10;
    e.to = 12;
    e.kind = EdgeKind::kLoop;
    e.active = false;
    e.query_keyframe = 2;
    e.match_keyframe = 0;
    e.error_translation = 0.25;
    e.error_rotation = 0.01;
    map.edges.push_back(e);
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(4, 30.0);
    for (std::uint32_t i = 0; i < 5; ++i) {
        auto k = std::make_shared<StoredKeyframe>();
        k->session = i == 4 ? 1 : 0;
        k->node = 10 + std::min<std::uint32_t>(i / 2, 2);
        k->data.id = i;
        k->data.scan_index = 100 + i;
        k->data.local_map_id = i / 2;
        k->data.stamp = 12.5 + i;
        k->data.T_odom_lidar = registration::test::xy_yaw(i, 0.5 * i, 3.0 * i);
        k->data.T_anchor_lidar = registration::test::xy_yaw(0.1 * i, 0, 1.0 * i);
        const std::vector<Eigen::Vector3f> pts =
            registration::test::view(scene, k->data.T_odom_lidar, 30.0);
        k->descriptor = places::make_scan_context(pts, map.descriptor_config);
        // Keyframe 1 has none (as a keyframe of a continued format-1 map).
        if (i != 1)
            k->localisation_descriptor =
                places::make_scan_context(pts, map.localisation_descriptor_config);
        if (i % 2 == 0) k->data.points = registration::test::every_nth(pts, 50, i);
        map.keyframes.push_back(k);
    }
    return map;
}

void expect_same_local_map(const common::LocalMapData& a, const common::LocalMapData& b) {
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.revision, b.revision);
    EXPECT_EQ(a.finished, b.finished);
    EXPECT_TRUE(a.T_odom_anchor.isApprox(b.T_odom_anchor, 0.0));
    EXPECT_TRUE(a.T_anchor_grid.isApprox(b.T_anchor_grid, 0.0));
    EXPECT_EQ(a.bbox_min, b.bbox_min);
    EXPECT_EQ(a.bbox_max, b.bbox_max);
    EXPECT_EQ(a.voxel_size, b.voxel_size);
    EXPECT_EQ(a.observation_times, b.observation_times);
    ASSERT_EQ(a.voxels.size(), b.voxels.size());
    for (std::size_t i = 0; i < a.voxels.size(); ++i) {
        const common::VoxelData &x = a.voxels[i], &y = b.voxels[i];
        ASSERT_TRUE(x.index == y.index && x.centre == y.centre && x.normal == y.normal &&
                    x.point_count == y.point_count && x.planarity == y.planarity &&
                    x.stability == y.stability && x.life.created == y.life.created &&
                    x.life.last_seen == y.life.last_seen &&
                    x.life.observations == y.life.observations && x.life.health == y.life.health &&
                    x.life.seen == y.life.seen)
            << "voxel " << i;
    }
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

void expect_same(const MapData& a, const MapData& b) {
    EXPECT_EQ(a.revision, b.revision);
    EXPECT_EQ(a.descriptor_config.kind, b.descriptor_config.kind);
    EXPECT_EQ(a.descriptor_config.rings, b.descriptor_config.rings);
    EXPECT_EQ(a.descriptor_config.sectors, b.descriptor_config.sectors);
    const places::ScanContextConfig &la = a.localisation_descriptor_config,
                                    &lb = b.localisation_descriptor_config;
    EXPECT_TRUE(la.kind == lb.kind && la.rings == lb.rings && la.sectors == lb.sectors &&
                la.max_range == lb.max_range && la.min_range == lb.min_range &&
                la.sensor_height == lb.sensor_height);
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
        EXPECT_EQ(a.nodes[i].id, b.nodes[i].id);
        EXPECT_EQ(a.nodes[i].local_map_id, b.nodes[i].local_map_id);
        EXPECT_EQ(a.nodes[i].session, b.nodes[i].session);
        EXPECT_EQ(a.nodes[i].fixed, b.nodes[i].fixed);
        EXPECT_TRUE(a.nodes[i].T_odom_anchor.isApprox(b.nodes[i].T_odom_anchor, 0.0));
        EXPECT_TRUE(a.nodes[i].T_world_anchor.isApprox(b.nodes[i].T_world_anchor, 0.0));
    }
    ASSERT_EQ(a.edges.size(), b.edges.size());
    for (std::size_t i = 0; i < a.edges.size(); ++i) {
        const PoseGraphEdge &x = a.edges[i], &y = b.edges[i];
        EXPECT_TRUE(x.from == y.from && x.to == y.to && x.kind == y.kind && x.active == y.active &&
                    x.information == y.information && x.query_keyframe == y.query_keyframe &&
                    x.match_keyframe == y.match_keyframe &&
                    x.error_translation == y.error_translation &&
                    x.error_rotation == y.error_rotation && x.T_from_to.isApprox(y.T_from_to, 0.0))
            << "edge " << i;
    }
    ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
    for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
        const StoredKeyframe &x = *a.keyframes[i], &y = *b.keyframes[i];
        EXPECT_TRUE(x.session == y.session && x.node == y.node && x.data.id == y.data.id &&
                    x.data.scan_index == y.data.scan_index &&
                    x.data.local_map_id == y.data.local_map_id && x.data.stamp == y.data.stamp &&
                    x.data.T_odom_lidar.isApprox(y.data.T_odom_lidar, 0.0) &&
                    x.data.T_anchor_lidar.isApprox(y.data.T_anchor_lidar, 0.0) &&
                    x.data.points == y.data.points && x.descriptor.kind == y.descriptor.kind &&
                    x.descriptor.value == y.descriptor.value &&
                    x.descriptor.spread == y.descriptor.spread &&
                    x.descriptor.occupied == y.descriptor.occupied)
            << "keyframe " << i;
        const places::ScanContext &u = x.localisation_descriptor, &v = y.localisation_descriptor;
        EXPECT_TRUE(u.kind == v.kind && u.rings == v.rings && u.sectors == v.sectors &&
                    same_bits(u.value, v.value) && same_bits(u.spread, v.spread) &&
                    u.occupied == v.occupied)
            << "keyframe " << i << ": localisation descriptor";
    }
    ASSERT_EQ(a.local_maps.size(), b.local_maps.size());
    for (std::size_t i = 0; i < a.local_maps.size(); ++i) {
        EXPECT_EQ(a.local_maps[i].node, b.local_maps[i].node);
        EXPECT_EQ(a.local_maps[i].session, b.local_maps[i].session);
        expect_same_local_map(*a.local_maps[i].data, *b.local_maps[i].data);
    }
}

std::string local_map_file(const fs::path& dir, std::uint64_t node) {
    for (const auto& e : fs::directory_iterator(dir / "local_maps")) {
        const std::string name = e.path().filename().string();
        if (name.rfind("lm_" + std::string(8 - std::to_string(node).size(), '0') +
                           std::to_string(node) + "_",
                       0) == 0) {
            return "local_maps/" + name;
        }
    }
    return "";
}

void flip_byte(const fs::path& file, std::uint64_t offset) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(std::streamoff(offset));
    char c = 0;
    f.read(&c, 1);
    c = char(c ^ 0x5A);
    f.seekp(std::streamoff(offset));
    f.write(&c, 1);
}

TEST(MapStore, SavedMapReloadsIdentical) {
    const fs::path dir = fresh_dir("identical");
    const MapData map = sample_map();
    const SaveStats s = save_map(dir.string(), map);
    EXPECT_EQ(s.files_written, 1u + 1u + 3u + 1u);  // graph, keyframes, 3 local maps, manifest
    const LoadedMap loaded = load_map(dir.string());
    EXPECT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    expect_same(map, loaded.map);
    // Saved again from what was loaded: the same files, byte for byte.
    const fs::path again = fresh_dir("identical_again");
    save_map(again.string(), loaded.map);
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        const fs::path other = again / fs::relative(e.path(), dir);
        ASSERT_TRUE(fs::exists(other)) << other;
        EXPECT_EQ(common::read_file(e.path().string(), "a"), common::read_file(other.string(), "b"))
            << other;
    }
}

TEST(MapStore, OnlyChangedFilesAreWrittenAndStaleOnesRemoved) {
    const fs::path dir = fresh_dir("incremental");
    MapData map = sample_map();
    MapWriter writer(dir.string(), SaveOptions{2});
    const SaveStats first = writer.save(map);
    EXPECT_EQ(first.files_written,
              1u + 3u + 3u + 1u);  // graph, 3 keyframe chunks, 3 maps, manifest
    const SaveStats same = writer.save(map);
    EXPECT_EQ(same.files_written, 1u);  // the manifest only
    EXPECT_EQ(same.files_removed, 0u);
    const std::string old_file = local_map_file(dir, 11);
    map.local_maps[1].data = random_local_map(1, 99, 10);  // a new snapshot of one map
    map.revision = 6;
    const SaveStats changed = writer.save(map);
    EXPECT_EQ(changed.files_written, 3u);  // that map, the graph (new revision), the manifest
    EXPECT_EQ(changed.files_removed, 2u);  // the old map file and the old graph
    EXPECT_FALSE(fs::exists(dir / old_file));
    expect_same(map, load_map(dir.string()).map);
}

// A save in pieces (issue 28): `between` after each file encoded, none for what is kept, and
// the manifest (written last) after the last piece.
TEST(MapStore, BetweenComesAfterEachFileEncoded) {
    const fs::path dir = fresh_dir("between");
    MapData map = sample_map();
    MapWriter writer(dir.string(), SaveOptions{2});
    std::size_t calls = 0;
    bool manifest_before_last = false;
    const auto between = [&] {
        ++calls;
        manifest_before_last = manifest_before_last || fs::exists(dir / "manifest.txt");
    };
    EXPECT_EQ(writer.save(map, between).files_written, 8u);
    EXPECT_EQ(calls, 7u);  // graph, 3 keyframe chunks, 3 maps: not the manifest
    EXPECT_FALSE(manifest_before_last);
    calls = 0;
    writer.save(map, between);
    EXPECT_EQ(calls, 1u);  // the graph (encoded to compare, not written again); nothing else
    map.local_maps[1].data = random_local_map(1, 99, 10);
    map.revision = 6;
    calls = 0;
    writer.save(map, between);
    EXPECT_EQ(calls, 2u);  // that map and the graph
    expect_same(map, load_map(dir.string()).map);
}

TEST(MapStore, AKeyframeReplacedInTheMiddleOfAChunkIsWritten) {
    // The long-term folding moves a folded map's keyframes to the node it went into: new objects
    // in the middle of a chunk whose first and last stay. A writer that compared only those kept
    // the old chunk, whose keyframes named a node the graph no longer had (site_week day 2).
    const fs::path dir = fresh_dir("middle");
    MapData map = sample_map();
    ASSERT_GE(map.keyframes.size(), 3u);
    MapWriter writer(dir.string(), SaveOptions{1000});
    writer.save(map);
    const std::size_t mid = map.keyframes.size() / 2;
    const std::uint64_t other = map.keyframes.front()->node != map.keyframes[mid]->node
                                    ? map.keyframes.front()->node
                                    : map.keyframes.back()->node;
    ASSERT_NE(other, map.keyframes[mid]->node) << "the sample needs keyframes of two nodes";
    auto moved = std::make_shared<StoredKeyframe>(*map.keyframes[mid]);
    moved->node = other;
    map.keyframes[mid] = moved;
    map.revision += 1;
    writer.save(map);
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    ASSERT_EQ(loaded.map.keyframes.size(), map.keyframes.size());
    EXPECT_EQ(loaded.map.keyframes[mid]->node, other);
}

TEST(MapStore, DamagedLocalMapIsRefusedAndTheRestLoads) {
    const fs::path dir = fresh_dir("damaged");
    const MapData map = sample_map();
    save_map(dir.string(), map);
    const std::string victim = local_map_file(dir, 11);
    ASSERT_FALSE(victim.empty());
    // A byte in the middle of the voxels.
    flip_byte(dir / victim, fs::file_size(dir / victim) / 2);
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_EQ(loaded.refused.size(), 1u);
    const std::string& why = loaded.refused[0];
    EXPECT_NE(why.find(victim + ": voxels["), std::string::npos) << why;
    EXPECT_NE(why.find("checksum mismatch over bytes"), std::string::npos) << why;
    // Everything else is there and unchanged.
    MapData expected = map;
    expected.local_maps.erase(expected.local_maps.begin() + 1);
    expect_same(expected, loaded.map);
}

TEST(MapStore, InvalidFieldIsNamedWithItsOffset) {
    auto m = std::make_shared<common::LocalMapData>(*random_local_map(3, 1, 50));
    m->voxels[17].normal = Eigen::Vector3f(2.0f, 0.0f, 0.0f);  // not a unit vector
    const std::string bytes = encode_local_map({4, 0, m});
    try {
        decode_local_map(bytes, "lm.bin");
        FAIL() << "an invalid normal was accepted";
    } catch (const MapFormatError& e) {
        EXPECT_EQ(e.field(), "voxels[17].normal");
        // The offset points at the stored value itself.
        float x = 0.0f;
        std::memcpy(&x, bytes.data() + e.offset(), 4);
        EXPECT_EQ(x, 2.0f);
        EXPECT_NE(std::string(e.what()).find("lm.bin: voxels[17].normal at byte "),
                  std::string::npos);
    }
    // A centre outside its cell, and a life record seen before it was created.
    auto c = std::make_shared<common::LocalMapData>(*random_local_map(3, 1, 50));
    c->voxels[3].centre.x() += 5.0f;
    EXPECT_THROW(decode_local_map(encode_local_map({4, 0, c}), "x"), MapFormatError);
    auto t = std::make_shared<common::LocalMapData>(*random_local_map(3, 1, 50));
    t->voxels[8].life.last_seen = t->voxels[8].life.created - 1.0;
    try {
        decode_local_map(encode_local_map({4, 0, t}), "y");
        FAIL();
    } catch (const MapFormatError& e) {
        EXPECT_EQ(e.field(), "voxels[8].life.last_seen");
    }
}

TEST(MapStore, CountsBeyondTheFileAreRefusedBeforeAnythingIsAllocated) {
    std::string bytes = encode_local_map({4, 0, random_local_map(3, 1, 50)});
    // The header section (from byte 16): node, session, id, revision, finished, two poses, the
    // box, the voxel size, then the observation count at byte 285. A count of 2^32 - 1 under a
    // valid checksum.
    const std::uint32_t huge = 0xFFFFFFFFu;
    std::memcpy(&bytes[285], &huge, 4);
    std::uint32_t length = 0;
    std::memcpy(&length, &bytes[12], 4);
    const std::uint32_t crc = common::crc32(bytes.data() + 16, length);
    std::memcpy(&bytes[16 + length], &crc, 4);
    try {
        decode_local_map(bytes, "lm.bin");
        FAIL() << "a count beyond the file was accepted";
    } catch (const MapFormatError& e) {
        EXPECT_EQ(e.field(), "header.observation_count");
        EXPECT_EQ(e.offset(), 285u);
        EXPECT_NE(std::string(e.what()).find("4294967295 observation times cannot fit"),
                  std::string::npos)
            << e.what();
    }
}

TEST(MapStore, TruncatedOrMismatchedFilesAreRefused) {
    const fs::path dir = fresh_dir("truncated");
    save_map(dir.string(), sample_map());
    const std::string victim = local_map_file(dir, 12);
    fs::resize_file(dir / victim, fs::file_size(dir / victim) - 100);
    const std::string other = local_map_file(dir, 10);
    // A file replaced by another valid local map: its checksum differs from the manifest's.
    {
        const std::string bytes = encode_local_map({10, 0, random_local_map(0, 1234, 20)});
        std::ofstream(dir / other, std::ios::binary | std::ios::trunc) << bytes;
    }
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_EQ(loaded.refused.size(), 2u);
    const std::string all = loaded.refused[0] + "\n" + loaded.refused[1];
    EXPECT_NE(all.find(victim + ": voxels["), std::string::npos) << all;
    EXPECT_NE(all.find("truncated"), std::string::npos) << all;  // the last section is cut
    EXPECT_NE(all.find(other + ": size: "), std::string::npos) << all;
    EXPECT_EQ(loaded.map.local_maps.size(), 1u);
    EXPECT_EQ(loaded.map.nodes.size(), 3u);
}

TEST(MapStore, DamagedManifestOrGraphFailsTheLoadWithAPreciseMessage) {
    const fs::path dir = fresh_dir("manifest");
    save_map(dir.string(), sample_map());
    const std::string manifest = common::read_file((dir / "manifest.txt").string(), "m");
    // Truncated (no end line).
    std::ofstream(dir / "manifest.txt", std::ios::trunc) << manifest.substr(0, manifest.size() / 2);
    try {
        load_map(dir.string());
        FAIL();
    } catch (const MapFormatError& e) {
        EXPECT_NE(std::string(e.what()).find("manifest.txt"), std::string::npos) << e.what();
    }
    // A malformed line is named by its number.
    std::string bad = manifest;
    bad.replace(bad.find("revision"), 8, "revisoin");
    std::ofstream(dir / "manifest.txt", std::ios::trunc) << bad;
    try {
        load_map(dir.string());
        FAIL();
    } catch (const MapFormatError& e) {
        EXPECT_NE(std::string(e.what()).find("manifest.txt: line 2 at byte"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("unknown entry 'revisoin'"), std::string::npos);
    }
    // A damaged graph: nothing can be placed.
    std::ofstream(dir / "manifest.txt", std::ios::trunc) << manifest;
    std::string graph;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().filename().string().rfind("graph_", 0) == 0)
            graph = e.path().filename().string();
    }
    flip_byte(dir / graph, 60);  // inside the first nodes section
    try {
        load_map(dir.string());
        FAIL();
    } catch (const MapFormatError& e) {
        EXPECT_EQ(e.file(), graph);
        EXPECT_NE(std::string(e.what()).find("nodes[0..2]"), std::string::npos) << e.what();
    }
    EXPECT_THROW(load_map((dir / "nowhere").string()), MapFormatError);
}

TEST(MapStore, Format2KeepsTheLocalisationDescriptorsBitForBit) {
    const fs::path dir = fresh_dir("format2");
    const MapData map = sample_map();
    ASSERT_FALSE(map.keyframes[0]->localisation_descriptor.empty());
    ASSERT_FALSE(map.keyframes[0]->localisation_descriptor.spread.empty());
    save_map(dir.string(), map);
    const std::string manifest = common::read_file((dir / "manifest.txt").string(), "m");
    EXPECT_EQ(manifest.rfind("ltm_map 2\n", 0), 0u) << manifest;
    EXPECT_NE(manifest.find("\nlocalisation_descriptor 1 8 30 80 0 2\n"), std::string::npos)
        << manifest;
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    expect_same(map, loaded.map);  // bit for bit, keyframe 1's empty descriptor included
    EXPECT_TRUE(loaded.map.keyframes[1]->localisation_descriptor.empty());
    // Every float as it was, NaN-free values compared by their bits.
    for (std::size_t i = 0; i < map.keyframes.size(); ++i) {
        EXPECT_TRUE(same_bits(map.keyframes[i]->localisation_descriptor.value,
                              loaded.map.keyframes[i]->localisation_descriptor.value));
    }
}

TEST(MapStore, Format4RecordsTheSessionsThatBuiltTheMapAndLoadsThemBack) {
    const fs::path dir = fresh_dir("format4");
    MapData map = sample_map();
    map.sessions = {{0, 0.5, 120.25, 2, 0}, {1, 86400.0, 86460.0, 0, 2}};
    save_map(dir.string(), map);
    const std::string manifest = common::read_file((dir / "manifest.txt").string(), "m");
    EXPECT_EQ(manifest.rfind("ltm_map 4\n", 0), 0u) << manifest;
    EXPECT_NE(manifest.find("\nsession 1 86400 86460 0 2\n"), std::string::npos) << manifest;
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    expect_same(map, loaded.map);
    ASSERT_EQ(loaded.map.sessions.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        const SessionRecord &a = map.sessions[i], &b = loaded.map.sessions[i];
        EXPECT_EQ(a.id, b.id);
        EXPECT_EQ(a.first_stamp, b.first_stamp);
        EXPECT_EQ(a.last_stamp, b.last_stamp);
        EXPECT_EQ(a.local_maps_added, b.local_maps_added);
        EXPECT_EQ(a.local_maps_updated, b.local_maps_updated);
    }
    // Saved again unchanged: the same files.
    const SaveStats again = save_map(dir.string(), loaded.map);
    EXPECT_EQ(again.files_written, 1u);  // the manifest only
    EXPECT_EQ(common::read_file((dir / "manifest.txt").string(), "m"), manifest);
}

TEST(MapStore, WithoutLocalisationDescriptorsAMapIsSavedInFormat1) {
    const fs::path dir = fresh_dir("format1");
    MapData map = sample_map();
    map.localisation_descriptor_config = no_localisation_descriptors();
    for (auto& k : map.keyframes) {
        auto copy = std::make_shared<StoredKeyframe>(*k);
        copy->localisation_descriptor = places::ScanContext();
        k = copy;
    }
    save_map(dir.string(), map);
    const std::string manifest = common::read_file((dir / "manifest.txt").string(), "m");
    EXPECT_EQ(manifest.rfind("ltm_map 1\nrevision 5\ndescriptor 1 10 24 80 0 2\ngraph ", 0), 0u)
        << manifest;
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    expect_same(map, loaded.map);
    EXPECT_FALSE(has_localisation_descriptors(loaded.map.localisation_descriptor_config));
}

TEST(MapStore, UnknownFormatVersionIsRefusedInOneLine) {
    const fs::path dir = fresh_dir("version");
    save_map(dir.string(), sample_map());
    const std::string manifest = common::read_file((dir / "manifest.txt").string(), "m");
    for (const char* version : {"0", "5"}) {
        std::string text = manifest;
        text.replace(0, 9, std::string("ltm_map ") + version);
        std::ofstream(dir / "manifest.txt", std::ios::trunc) << text;
        try {
            load_map(dir.string());
            ADD_FAILURE() << "format version " << version << " accepted";
        } catch (const MapFormatError& e) {
            EXPECT_EQ(std::string(e.what()),
                      std::string("manifest.txt: line 1 at byte 0: format version ") + version +
                          " is not supported (this build reads versions 1 to 4)");
        }
    }
    std::ofstream(dir / "manifest.txt", std::ios::trunc) << manifest;
    // A binary file of another version (the version field is outside the checksummed sections).
    const std::string victim = local_map_file(dir, 11);
    {
        std::fstream f(dir / victim, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(8);
        const std::uint32_t five = 5;
        f.write(reinterpret_cast<const char*>(&five), 4);
    }
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_EQ(loaded.refused.size(), 1u);
    EXPECT_EQ(loaded.refused[0], victim +
                                     ": format version at byte 8: format version 5 is not "
                                     "supported (this build reads versions 1 to 4)");
}

TEST(MapStore, DamagedLocalisationDescriptorIsRefusedNamingTheField) {
    const MapData map = sample_map();
    const DescriptorSettings settings{map.descriptor_config, map.localisation_descriptor_config};
    auto decode_error = [&](const StoredKeyframe& k) -> std::string {
        std::vector<std::shared_ptr<const StoredKeyframe>> list{
            std::make_shared<StoredKeyframe>(k)};
        const std::string bytes = encode_keyframes(settings, list, 0, 1);
        std::uint64_t first = 0;
        try {
            decode_keyframes(bytes, "kf.bin", &settings, &first);
        } catch (const MapFormatError& e) {
            return e.field() + ": " + e.problem();
        }
        return "";
    };
    StoredKeyframe k = *map.keyframes[0];
    EXPECT_EQ(decode_error(k), "");
    k.localisation_descriptor.spread[17] = -0.5f;
    EXPECT_EQ(decode_error(k), "keyframes[0].localisation_descriptor.spread: negative");
    k = *map.keyframes[0];
    k.localisation_descriptor.occupied[3] = 2;
    EXPECT_EQ(decode_error(k), "keyframes[0].localisation_descriptor.occupied: must be 0 or 1");
    k = *map.keyframes[0];
    k.localisation_descriptor.value[5] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(decode_error(k), "keyframes[0].localisation_descriptor.value: not a finite number");
    k = *map.keyframes[0];
    k.localisation_descriptor.rings = 7;  // the header says 8
    EXPECT_EQ(decode_error(k),
              "keyframes[0].localisation_descriptor: shape differs from the file header's");
    // The header's settings against the manifest's.
    DescriptorSettings other = settings;
    other.localisation.sectors = 60;
    std::vector<std::shared_ptr<const StoredKeyframe>> list{map.keyframes[0]};
    std::uint64_t first = 0;
    try {
        decode_keyframes(encode_keyframes(settings, list, 0, 1), "kf.bin", &other, &first);
        ADD_FAILURE() << "settings differing from the manifest's accepted";
    } catch (const MapFormatError& e) {
        EXPECT_EQ(e.field(), "header.localisation_descriptor");
    }
    // In a map folder: damage under a valid checksum is refused naming the field; the rest loads.
    const fs::path dir = fresh_dir("damaged_localisation");
    save_map(dir.string(), map);
    std::string file;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().filename().string().rfind("keyframes_", 0) == 0)
            file = e.path().filename().string();
    }
    std::string bytes = common::read_file((dir / file).string(), "kf");
    // keyframes[0]'s section: after the header section (16 + length + 4), its length, then ids
    // (4 + 8 + 8 + 8 + 8 + 8), two poses (192), the loop descriptor (9 + 240 * 9) and the
    // localisation descriptor's kind, rings, sectors (9): its first value.
    std::uint32_t header_length = 0;
    std::memcpy(&header_length, &bytes[12], 4);
    const std::size_t section = 16 + header_length + 4;
    const std::size_t value0 = section + 4 + 44 + 192 + 9 + 240 * 9 + 9;
    std::uint8_t rings = 0;
    std::memcpy(&rings, &bytes[value0 - 8], 1);
    ASSERT_EQ(rings, 8u);  // the layout above holds
    const std::size_t spread0 = value0 + 240 * 4;
    const float negative = -1.0f;
    std::memcpy(&bytes[spread0], &negative, 4);
    std::uint32_t length = 0;
    std::memcpy(&length, &bytes[section], 4);
    const std::uint32_t crc = common::crc32(bytes.data() + section + 4, length);
    std::memcpy(&bytes[section + 4 + length], &crc, 4);
    std::ofstream(dir / file, std::ios::binary | std::ios::trunc) << bytes;
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_EQ(loaded.refused.size(), 1u);
    EXPECT_EQ(loaded.refused[0], file + ": keyframes[0].localisation_descriptor.spread at byte " +
                                     std::to_string(spread0) + ": negative");
    EXPECT_EQ(loaded.map.local_maps.size(), 3u);
}

// Format 4 (compact files): a map that records sessions, its local maps' voxels and keyframes
// compressed. Bit for bit the same map back, in fewer bytes than format 2's rows.
TEST(MapStore, Format4IsCompactAndComesBackBitForBit) {
    const fs::path dir = fresh_dir("format4_compact");
    MapData map = sample_map();
    map.sessions = {{0, 0.5, 120.25, 2, 0}, {1, 86400.0, 86460.0, 0, 2}};
    // Times that are observation times (stored as their index) beside times that are not.
    auto lm = std::make_shared<common::LocalMapData>(*map.local_maps[1].data);
    for (std::size_t i = 0; i < lm->voxels.size(); i += 2) {
        lm->voxels[i].life.created = lm->observation_times[i % 20];
        lm->voxels[i].life.last_seen = lm->observation_times[std::min<std::size_t>(19, i % 20 + 3)];
        lm->voxels[i].normal.z() = -lm->voxels[i].normal.z();  // normals facing down too
    }
    map.local_maps[1].data = lm;
    save_map(dir.string(), map);
    const LoadedMap loaded = load_map(dir.string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    expect_same(map, loaded.map);
    for (const StoredLocalMap& m : map.local_maps) {
        const std::uint64_t file = fs::file_size(dir / local_map_file(dir, m.node));
        EXPECT_EQ(file, encode_local_map(m, 4).size());
        EXPECT_LT(double(file), 0.75 * double(encode_local_map(m, 2).size())) << m.node;
    }
    // Saved again: byte for byte the same files (a site's unchanged files stay hard links).
    const fs::path again = fresh_dir("format4_again");
    save_map(again.string(), loaded.map);
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        const fs::path rel = fs::relative(e.path(), dir);
        EXPECT_EQ(common::read_file(e.path().string(), "a"),
                  common::read_file((again / rel).string(), "b"))
            << rel;
    }
}

// Recomputes every section's CRC of a map file (what a bug, not the disk, would write).
void fix_checksums(std::string& bytes) {
    std::size_t at = 12;  // magic, version
    while (at + 8 <= bytes.size()) {
        std::uint32_t len = 0;
        std::memcpy(&len, bytes.data() + at, 4);
        if (at + 8 + len > bytes.size()) return;
        const std::uint32_t crc = common::crc32(bytes.data() + at + 4, len);
        std::memcpy(&bytes[at + 4 + len], &crc, 4);
        at += 8 + std::size_t(len);
    }
}

// A damaged compressed local map or keyframe file, even under good checksums, is refused in one
// line (the rest loads), never a crash.
TEST(MapStore, Format4DamageInsideAFrameIsOneLine) {
    const fs::path dir = fresh_dir("format4_damage");
    MapData map = sample_map();
    map.sessions = {{0, 0.5, 120.25, 2, 0}, {1, 86400.0, 86460.0, 0, 2}};
    save_map(dir.string(), map);
    std::string keyframes;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind("keyframes_", 0) == 0)
            keyframes = e.path().filename().string();
    ASSERT_FALSE(keyframes.empty());
    std::mt19937 rng(3);
    for (const std::string& victim : {local_map_file(dir, 11), keyframes}) {
        const fs::path path = dir / victim;
        const std::string good = common::read_file(path.string(), "good");
        std::size_t refused = 0;
        for (int trial = 0; trial < 40; ++trial) {
            std::string bad = good;
            // A byte of the last section's body (the frame), after its first 24 bytes.
            std::size_t at = 12, last = 12;
            while (at + 8 <= good.size()) {
                std::uint32_t len = 0;
                std::memcpy(&len, good.data() + at, 4);
                last = at;
                at += 8 + std::size_t(len);
            }
            std::uint32_t len = 0;
            std::memcpy(&len, good.data() + last, 4);
            const std::size_t pos =
                last + 4 + std::uniform_int_distribution<std::size_t>(0, len - 1)(rng);
            bad[pos] = char(bad[pos] ^ (1 + trial % 255));
            if (trial % 2 == 0) fix_checksums(bad);
            common::write_file_atomic(path.string(), bad);
            const LoadedMap loaded = load_map(dir.string());
            if (!loaded.refused.empty()) {
                ++refused;
                ASSERT_EQ(loaded.refused.size(), 1u);
                EXPECT_EQ(loaded.refused[0].find('\n'), std::string::npos) << loaded.refused[0];
                EXPECT_EQ(loaded.refused[0].rfind(victim, 0), 0u) << loaded.refused[0];
            }
        }
        EXPECT_GE(refused, 20u) << victim;  // every damage the CRC sees, and more
        common::write_file_atomic(path.string(), good);
    }
    expect_same(map, load_map(dir.string()).map);
}

}  // namespace
}  // namespace ltm::map
