// Old map files still load: testdata/map_v1 was written by the format-1 MapWriter of commit
// 79f6a21 (before the map records were described once for both directions) from fixture_map()
// below, with two keyframes a file. Loading it must give fixture_map() back, and saving what was
// loaded must give the same bytes again (the format is unchanged).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "map/core/map_store.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::map {
namespace {

namespace fs = std::filesystem;

// Deterministic numbers without <random> (its distributions are not portable): [0, 1).
float unit(std::uint32_t k) { return float((k * 2654435761u) >> 8) / float(1u << 24); }

std::shared_ptr<const common::LocalMapData> fixture_local_map(std::uint64_t id,
                                                              std::size_t voxels) {
    auto m = std::make_shared<common::LocalMapData>();
    m->id = id;
    m->revision = std::uint32_t(2 + id);
    m->finished = id != 1;
    m->T_odom_anchor = registration::test::xy_yaw(12.0 * id, 1.5, 20.0 * id);
    m->T_anchor_grid = registration::test::xy_yaw(-0.25, 0.5, -10.0 * id);
    m->bbox_min = Eigen::Vector3d(-40, -40, -8);
    m->bbox_max = Eigen::Vector3d(40, 40, 12);
    m->voxel_size = 0.5f;
    const std::size_t times = voxels == 0 ? 0 : 12;
    for (std::size_t i = 0; i < times; ++i) m->observation_times.push_back(50.0 + 0.1 * i);
    for (std::uint32_t i = 0; i < voxels; ++i) {
        const std::uint32_t k = 1000 * std::uint32_t(id) + 7 * i;
        common::VoxelData v;
        v.index = Eigen::Vector3i(int(i % 40) - 20, int(i / 40) - 5, int(i % 9) - 4);
        v.centre =
            (v.index.cast<float>() + Eigen::Vector3f(unit(k), unit(k + 1), unit(k + 2))) * 0.5f;
        v.normal = i % 6 == 0
                       ? Eigen::Vector3f::Zero()
                       : Eigen::Vector3f(unit(k + 3) - 0.5f, unit(k + 4) - 0.5f, 1.0f).normalized();
        v.point_count = 1 + i % 50;
        v.planarity = unit(k + 5);
        v.stability = unit(k + 6);
        v.life.created = 50.0 + unit(k + 7);
        v.life.last_seen = v.life.created + 0.25 * (i % 3);
        v.life.observations = i % 11;
        v.life.health = unit(k + 8);
        for (std::uint16_t s = 0; s < i % 4; ++s)
            v.life.seen.push_back(std::uint16_t((s * 5 + i) % times));
        m->voxels.push_back(v);
    }
    return m;
}

std::shared_ptr<const StoredKeyframe> fixture_keyframe(std::uint32_t i,
                                                       const places::ScanContextConfig& config) {
    auto k = std::make_shared<StoredKeyframe>();
    k->session = i == 2 ? 1 : 0;
    k->node = 20 + i;
    k->data.id = i;
    k->data.scan_index = 40 + 3 * i;
    k->data.local_map_id = i;
    k->data.stamp = 50.5 + i;
    k->data.T_odom_lidar = registration::test::xy_yaw(2.0 * i, 0.5, 4.0 * i);
    k->data.T_anchor_lidar = registration::test::xy_yaw(0.2 * i, -0.1, 1.5 * i);
    places::ScanContext& sc = k->descriptor;
    sc.kind = config.kind;
    sc.rings = config.rings;
    sc.sectors = config.sectors;
    const std::size_t bins = std::size_t(config.rings) * std::size_t(config.sectors);
    for (std::uint32_t b = 0; b < bins; ++b) {
        const bool occupied = (b + i) % 3 != 0;
        sc.value.push_back(occupied ? 4.0f * unit(100 * i + b) : 0.0f);
        sc.spread.push_back(occupied ? unit(100 * i + b + 50) : 0.0f);
        sc.occupied.push_back(occupied ? 1 : 0);
    }
    if (i != 1) {
        for (std::uint32_t p = 0; p < 40; ++p) {
            k->data.points.emplace_back(20.0f * unit(p + 10 * i) - 10.0f,
                                        20.0f * unit(p + 10 * i + 3) - 10.0f, unit(p + 5));
        }
    }
    return k;
}

// Three nodes (two sessions), an odometry and an inactive loop edge, three keyframes (two files
// at two keyframes a file), local maps of 220, 300 and no voxels.
MapData fixture_map() {
    MapData map;
    map.revision = 3;
    map.descriptor_config.kind = places::ScanContextKind::kMeanVariance;
    map.descriptor_config.rings = 6;
    map.descriptor_config.sectors = 12;
    map.descriptor_config.max_range = 60.0;
    map.descriptor_config.sensor_height = 1.73;
    const std::size_t voxels[3] = {220, 300, 0};
    for (std::uint64_t n = 0; n < 3; ++n) {
        PoseGraphNode node;
        node.id = 20 + n;
        node.local_map_id = n;
        node.session = n == 2 ? 1 : 0;
        node.fixed = n == 0;
        node.T_odom_anchor = registration::test::xy_yaw(12.0 * n, 1.5, 20.0 * n);
        node.T_world_anchor = registration::test::xy_yaw(12.0 * n + 0.3, 1.25, 20.0 * n - 2.0);
        map.nodes.push_back(node);
        map.local_maps.push_back({node.id, node.session, fixture_local_map(n, voxels[n])});
        map.keyframes.push_back(fixture_keyframe(std::uint32_t(n), map.descriptor_config));
    }
    PoseGraphEdge e;
    e.from = 20;
    e.to = 21;
    e.T_from_to = registration::test::xy_yaw(12, 0, 20);
    e.information = Matrix6d::Identity() * 50.0;
    e.information(2, 4) = e.information(4, 2) = -1.5;
    map.edges.push_back(e);
    e.from = 21;
    e.to = 22;
    e.kind = EdgeKind::kLoop;
    e.active = false;
    e.query_keyframe = 2;
    e.match_keyframe = 1;
    e.error_translation = 0.125;
    e.error_rotation = 0.0625;
    map.edges.push_back(e);
    return map;
}

const fs::path kFixture = fs::path(LTM_SOURCE_DIR) / "components/map/core/testdata/map_v1";

std::string file_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void expect_same_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    EXPECT_LT((a.matrix() - b.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

void expect_same_local_map(const common::LocalMapData& a, const common::LocalMapData& b) {
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.revision, b.revision);
    EXPECT_EQ(a.finished, b.finished);
    expect_same_pose(a.T_odom_anchor, b.T_odom_anchor);
    expect_same_pose(a.T_anchor_grid, b.T_anchor_grid);
    EXPECT_EQ(a.bbox_min, b.bbox_min);
    EXPECT_EQ(a.bbox_max, b.bbox_max);
    EXPECT_EQ(a.voxel_size, b.voxel_size);
    EXPECT_EQ(a.observation_times, b.observation_times);
    ASSERT_EQ(a.voxels.size(), b.voxels.size());
    for (std::size_t i = 0; i < a.voxels.size(); ++i) {
        const common::VoxelData &u = a.voxels[i], &v = b.voxels[i];
        EXPECT_EQ(u.index, v.index) << i;
        EXPECT_EQ(u.centre, v.centre) << i;
        EXPECT_EQ(u.normal, v.normal) << i;
        EXPECT_EQ(u.point_count, v.point_count) << i;
        EXPECT_EQ(u.planarity, v.planarity) << i;
        EXPECT_EQ(u.stability, v.stability) << i;
        EXPECT_EQ(u.life.created, v.life.created) << i;
        EXPECT_EQ(u.life.last_seen, v.life.last_seen) << i;
        EXPECT_EQ(u.life.observations, v.life.observations) << i;
        EXPECT_EQ(u.life.health, v.life.health) << i;
        EXPECT_EQ(u.life.seen, v.life.seen) << i;
    }
}

TEST(MapFilesV1, LoadAsTheMapTheyWereWrittenFrom) {
    const LoadedMap loaded = load_map(kFixture.string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    const MapData expected = fixture_map();
    const MapData& map = loaded.map;
    EXPECT_EQ(map.revision, expected.revision);
    const places::ScanContextConfig &c = map.descriptor_config, &e = expected.descriptor_config;
    EXPECT_EQ(c.kind, e.kind);
    EXPECT_EQ(c.rings, e.rings);
    EXPECT_EQ(c.sectors, e.sectors);
    EXPECT_EQ(c.max_range, e.max_range);
    EXPECT_EQ(c.min_range, e.min_range);
    EXPECT_EQ(c.sensor_height, e.sensor_height);
    ASSERT_EQ(map.nodes.size(), expected.nodes.size());
    for (std::size_t i = 0; i < map.nodes.size(); ++i) {
        EXPECT_EQ(map.nodes[i].id, expected.nodes[i].id);
        EXPECT_EQ(map.nodes[i].session, expected.nodes[i].session);
        EXPECT_EQ(map.nodes[i].local_map_id, expected.nodes[i].local_map_id);
        EXPECT_EQ(map.nodes[i].fixed, expected.nodes[i].fixed);
        expect_same_pose(map.nodes[i].T_odom_anchor, expected.nodes[i].T_odom_anchor);
        expect_same_pose(map.nodes[i].T_world_anchor, expected.nodes[i].T_world_anchor);
    }
    ASSERT_EQ(map.edges.size(), expected.edges.size());
    for (std::size_t i = 0; i < map.edges.size(); ++i) {
        const PoseGraphEdge &a = map.edges[i], &b = expected.edges[i];
        EXPECT_EQ(a.from, b.from);
        EXPECT_EQ(a.to, b.to);
        EXPECT_EQ(a.kind, b.kind);
        EXPECT_EQ(a.active, b.active);
        expect_same_pose(a.T_from_to, b.T_from_to);
        EXPECT_EQ(a.information, b.information);
        EXPECT_EQ(a.query_keyframe, b.query_keyframe);
        EXPECT_EQ(a.match_keyframe, b.match_keyframe);
        EXPECT_EQ(a.error_translation, b.error_translation);
        EXPECT_EQ(a.error_rotation, b.error_rotation);
    }
    ASSERT_EQ(map.keyframes.size(), expected.keyframes.size());
    for (std::size_t i = 0; i < map.keyframes.size(); ++i) {
        const StoredKeyframe &a = *map.keyframes[i], &b = *expected.keyframes[i];
        EXPECT_EQ(a.session, b.session);
        EXPECT_EQ(a.node, b.node);
        EXPECT_EQ(a.data.id, b.data.id);
        EXPECT_EQ(a.data.scan_index, b.data.scan_index);
        EXPECT_EQ(a.data.local_map_id, b.data.local_map_id);
        EXPECT_EQ(a.data.stamp, b.data.stamp);
        expect_same_pose(a.data.T_odom_lidar, b.data.T_odom_lidar);
        expect_same_pose(a.data.T_anchor_lidar, b.data.T_anchor_lidar);
        EXPECT_EQ(a.data.points, b.data.points);
        EXPECT_EQ(a.descriptor.kind, b.descriptor.kind);
        EXPECT_EQ(a.descriptor.rings, b.descriptor.rings);
        EXPECT_EQ(a.descriptor.sectors, b.descriptor.sectors);
        EXPECT_EQ(a.descriptor.value, b.descriptor.value);
        EXPECT_EQ(a.descriptor.spread, b.descriptor.spread);
        EXPECT_EQ(a.descriptor.occupied, b.descriptor.occupied);
    }
    ASSERT_EQ(map.local_maps.size(), expected.local_maps.size());
    for (std::size_t i = 0; i < map.local_maps.size(); ++i) {
        EXPECT_EQ(map.local_maps[i].node, expected.local_maps[i].node);
        EXPECT_EQ(map.local_maps[i].session, expected.local_maps[i].session);
        expect_same_local_map(*map.local_maps[i].data, *expected.local_maps[i].data);
    }
}

// Format 1 holds no localisation descriptors: they load empty, and the map says it has none.
TEST(MapFilesV1, LoadWithoutLocalisationDescriptors) {
    const LoadedMap loaded = load_map(kFixture.string());
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    EXPECT_FALSE(has_localisation_descriptors(loaded.map.localisation_descriptor_config));
    EXPECT_EQ(loaded.map.localisation_descriptor_config.rings, 0);
    ASSERT_EQ(loaded.map.keyframes.size(), 3u);
    for (const auto& k : loaded.map.keyframes) {
        EXPECT_TRUE(k->localisation_descriptor.empty());
        EXPECT_FALSE(k->descriptor.empty());
    }
}

TEST(MapFilesV1, SavedAgainGiveTheSameBytes) {
    const LoadedMap loaded = load_map(kFixture.string());
    const fs::path again = fs::path(LTM_BINARY_DIR) / "map_test_maps" / "map_v1_again";
    fs::remove_all(again);
    SaveOptions options;
    options.keyframes_per_file = 2;
    save_map(again.string(), loaded.map, options);
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(kFixture)) {
        if (!e.is_regular_file() || e.path().extension() == ".md") continue;
        const fs::path other = again / fs::relative(e.path(), kFixture);
        ASSERT_TRUE(fs::exists(other)) << other;
        EXPECT_TRUE(file_bytes(e.path()) == file_bytes(other)) << other;
        ++files;
    }
    EXPECT_EQ(files, 1u + 1u + 2u + 3u);  // manifest, graph, two keyframe files, three local maps
}

}  // namespace
}  // namespace ltm::map
