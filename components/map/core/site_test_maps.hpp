#pragma once
// Tiny maps for the site tests: a chain of local maps, two keyframes each, and a maintained-map
// file (sections as the maintenance core frames them).
#include <filesystem>
#include <random>
#include <string>

#include "common/core/byte_io.hpp"
#include "common/core/file_io.hpp"
#include "map/core/map_data.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::map::test {

inline std::shared_ptr<const common::LocalMapData> tiny_local_map(std::uint64_t id,
                                                                  std::uint32_t seed,
                                                                  std::size_t voxels) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto m = std::make_shared<common::LocalMapData>();
    m->id = id;
    m->revision = seed;
    m->T_odom_anchor = registration::test::xy_yaw(10.0 * id, 0.0, 0.0);
    m->bbox_min = Eigen::Vector3d(-20, -20, -5);
    m->bbox_max = Eigen::Vector3d(20, 20, 5);
    m->voxel_size = 0.5f;
    m->observation_times.push_back(100.0);
    for (std::size_t i = 0; i < voxels; ++i) {
        common::VoxelData v;
        v.index = Eigen::Vector3i(int(i % 30) - 15, int(i / 30) - 10, 0);
        v.centre = (v.index.cast<float>() + Eigen::Vector3f(u(rng), u(rng), 0.5f)) * 0.5f;
        v.normal = Eigen::Vector3f::UnitZ();
        v.point_count = 3;
        v.planarity = 0.9f;
        v.stability = 0.8f;
        v.life.created = 100.0;
        v.life.last_seen = 100.5;
        v.life.observations = 2;
        v.life.health = 0.5f;
        m->voxels.push_back(v);
    }
    return m;
}

// `local_maps` local maps of session `session` (node ids from 0), two keyframes each along x.
inline MapData tiny_map(std::size_t local_maps, std::size_t voxels = 200, std::uint32_t seed = 1) {
    MapData map;
    map.revision = 1;
    map.descriptor_config.rings = 6;
    map.descriptor_config.sectors = 12;
    static const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(3, 30.0);
    for (std::uint64_t n = 0; n < local_maps; ++n) {
        PoseGraphNode node;
        node.id = n;
        node.local_map_id = n;
        node.T_odom_anchor = registration::test::xy_yaw(10.0 * n, 0, 0);
        node.T_world_anchor = node.T_odom_anchor;
        node.fixed = n == 0;
        map.nodes.push_back(node);
        map.local_maps.push_back({node.id, 0, tiny_local_map(n, seed + std::uint32_t(n), voxels)});
        if (n > 0) {
            PoseGraphEdge e;
            e.from = n - 1;
            e.to = n;
            e.T_from_to = registration::test::xy_yaw(10, 0, 0);
            map.edges.push_back(e);
        }
        for (std::uint64_t k = 0; k < 2; ++k) {
            auto kf = std::make_shared<StoredKeyframe>();
            kf->node = n;
            kf->data.id = 2 * n + k;
            kf->data.local_map_id = n;
            kf->data.stamp = 10.0 + double(2 * n + k);
            kf->data.T_anchor_lidar = registration::test::xy_yaw(5.0 * double(k), 0, 0);
            kf->data.T_odom_lidar = node.T_odom_anchor * kf->data.T_anchor_lidar;
            kf->descriptor = places::make_scan_context(
                registration::test::view(scene, kf->data.T_odom_lidar, 30.0),
                map.descriptor_config);
            map.keyframes.push_back(kf);
        }
    }
    return map;
}

// A maintained-map file as the maintenance core frames it: "LTMMAINT", version, two sections.
inline void write_maintained_map(const std::string& path, std::uint32_t fill) {
    common::ByteWriter w;
    w.raw("LTMMAINT", 8);
    w.value(std::uint32_t(1));
    w.section("header", [&](auto& s) { s.value(fill); });
    w.section("region", [&](auto& s) {
        for (std::uint32_t i = 0; i < 100; ++i) s.value(fill + i);
    });
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    common::write_file_atomic(path, w.bytes().data(), w.bytes().size());
}

}  // namespace ltm::map::test
