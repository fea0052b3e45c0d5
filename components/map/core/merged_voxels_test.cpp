#include "map/core/merged_voxels.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

namespace ltm::map {
namespace {

common::VoxelData voxel(const Eigen::Vector3f& centre, float planarity = 0.9f,
                        float health = 1.0f) {
    common::VoxelData v;
    v.centre = centre;
    v.index = centre.array().floor().cast<int>();
    v.normal = Eigen::Vector3f::UnitZ();
    v.point_count = 10;
    v.planarity = planarity;
    v.stability = 1.0f;
    v.life.health = health;
    v.life.seen = {0};
    return v;
}

void add_local_map(MapData& map, std::uint64_t node, std::uint32_t session,
                   const Eigen::Isometry3d& T_world_anchor, std::vector<common::VoxelData> voxels) {
    PoseGraphNode n;
    n.id = node;
    n.session = session;
    n.T_world_anchor = T_world_anchor;
    map.nodes.push_back(n);
    auto data = std::make_shared<common::LocalMapData>();
    data->id = node;
    data->voxel_size = 1.0f;
    data->voxels = std::move(voxels);
    map.local_maps.push_back({node, session, data});
}

Eigen::Isometry3d at(double x, double y) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, 0.0);
    return T;
}

TEST(MergedVoxels, ACellKeepsTheVoxelOfTheNearestAnchor) {
    MapData map;
    // Both local maps have a voxel in the world cell (5, 0, 0); anchor 2 is nearer to it.
    add_local_map(map, 1, 0, at(0, 0), {voxel({5.2f, 0.5f, 0.5f}), voxel({-3.5f, 0.5f, 0.5f})});
    add_local_map(map, 2, 1, at(8, 0), {voxel({-2.6f, 0.5f, 0.5f})});
    const MergedVoxels merged = merge_voxels(map, {});
    ASSERT_TRUE(merged.voxels);
    EXPECT_EQ(merged.local_maps, 2u);
    EXPECT_EQ(merged.sessions, 2u);
    EXPECT_TRUE(merged.voxels->finished);
    EXPECT_FLOAT_EQ(merged.voxels->voxel_size, 1.0f);
    ASSERT_EQ(merged.voxels->voxels.size(), 2u);
    const common::VoxelData& shared = merged.voxels->voxels[0];
    EXPECT_EQ(shared.index, Eigen::Vector3i(5, 0, 0));
    EXPECT_NEAR(shared.centre.x(), 5.4f, 1e-5f);  // anchor 2's: 8 - 2.6
    EXPECT_TRUE(shared.life.seen.empty());
    EXPECT_NEAR(merged.voxels->bbox_min.x(), -3.5, 1e-5);
    EXPECT_NEAR(merged.voxels->bbox_max.x(), 5.2, 1e-5);  // the first voxel set the bounds
}

TEST(MergedVoxels, LeavesOutFilteredVoxelsAndUnplacedLocalMaps) {
    MapData map;
    add_local_map(map, 1, 0, at(0, 0),
                  {voxel({1.5f, 0.5f, 0.5f}), voxel({2.5f, 0.5f, 0.5f}, 0.1f),
                   voxel({3.5f, 0.5f, 0.5f}, 0.9f, 0.2f)});
    add_local_map(map, 2, 0, at(0, 0), {voxel({9.5f, 0.5f, 0.5f})});
    map.nodes.pop_back();  // local map 2 has no node: not placed
    const MergedVoxels merged = merge_voxels(map, {0.5, 0.4});
    EXPECT_EQ(merged.local_maps, 1u);
    EXPECT_EQ(merged.sessions, 1u);
    ASSERT_EQ(merged.voxels->voxels.size(), 1u);
    EXPECT_NEAR(merged.voxels->voxels[0].centre.x(), 1.5f, 1e-5f);
    // Health weighs the stability.
    MapData weak;
    add_local_map(weak, 1, 0, at(0, 0), {voxel({1.5f, 0.5f, 0.5f}, 0.9f, 0.5f)});
    EXPECT_FLOAT_EQ(merge_voxels(weak, {}).voxels->voxels[0].stability, 0.5f);
}

// Many overlapping local maps (the cell table grows many times over): every cell keeps the
// voxel of the local map anchored nearest to it, as a brute force over the cells says, in the
// order the cells were first met.
TEST(MergedVoxels, ALargeMergeKeepsEveryCellsNearestAnchorsVoxel) {
    MapData map;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-40.0f, 40.0f);
    using Cell = std::tuple<int, int, int>;
    std::map<Cell, std::pair<float, Eigen::Vector3f>> nearest;  // distance, world centre
    std::vector<Cell> order;
    for (int m = 0; m < 6; ++m) {
        const Eigen::Isometry3d T = at(15.0 * m, 3.0 * m);
        std::vector<common::VoxelData> voxels;
        for (int i = 0; i < 20000; ++i) {
            const Eigen::Vector3f c(u(rng), u(rng), 0.1f * u(rng));
            voxels.push_back(voxel(c));
            const Eigen::Vector3f w = T.linear().cast<float>() * c + T.translation().cast<float>();
            const Eigen::Vector3i k = w.array().floor().cast<int>();
            const Cell cell{k.x(), k.y(), k.z()};
            const float d = (w - T.translation().cast<float>()).head<2>().norm();  // as merged
            const auto it = nearest.find(cell);
            if (it == nearest.end()) {
                nearest[cell] = {d, w};
                order.push_back(cell);
            } else if (d < it->second.first) {
                it->second = {d, w};
            }
        }
        add_local_map(map, std::uint64_t(m + 1), 0, T, std::move(voxels));
    }
    const MergedVoxels merged = merge_voxels(map, {});
    ASSERT_EQ(merged.voxels->voxels.size(), order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        const common::VoxelData& v = merged.voxels->voxels[i];
        EXPECT_EQ(Cell(v.index.x(), v.index.y(), v.index.z()), order[i]) << i;
        EXPECT_LT((v.centre - nearest[order[i]].second).norm(), 1e-4f) << i;
    }
}

}  // namespace
}  // namespace ltm::map
