#include "map/core/global_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>

#include "registration/core/test_data.hpp"

namespace ltm::map {
namespace {

common::LocalMapData scene_map(std::uint64_t id, const Eigen::Isometry3d& anchor) {
    const std::vector<Eigen::Vector3f> scene = registration::test::synthetic_scene(31, 40.0);
    std::vector<std::vector<Eigen::Vector3f>> scans = {
        registration::test::view(scene, anchor, 40.0)};
    return registration::test::build_local_map(id, anchor, scans, {anchor}, 1.0, 40.0);
}

TEST(GlobalMap, FusesOverlapsCellByCellAsABruteForceOracle) {
    const Eigen::Isometry3d a = registration::test::xy_yaw(0, 0, 0),
                            b = registration::test::xy_yaw(7.3, 2.1, 20);
    const common::LocalMapData ma = scene_map(0, a), mb = scene_map(1, b);
    std::vector<PlacedLocalMap> placed(2);
    placed[0].map = &ma;
    placed[0].T_world_anchor = ma.T_odom_anchor;
    placed[1].map = &mb;
    placed[1].T_world_anchor = mb.T_odom_anchor;
    GlobalMapStats stats;
    const common::PlyCloud cloud = build_global_map(placed, GlobalMapConfig(), &stats);
    // Oracle: the distinct world cells of every voxel with a normal.
    std::set<std::tuple<int, int, int>> cells;
    std::size_t with_normal = 0;
    for (const PlacedLocalMap& p : placed) {
        for (const common::VoxelData& v : p.map->voxels) {
            if (v.normal.squaredNorm() < 0.5f) continue;
            ++with_normal;
            const Eigen::Vector3d w =
                p.T_world_anchor * p.map->T_anchor_grid * v.centre.cast<double>();
            cells.emplace(int(std::floor(w.x())), int(std::floor(w.y())), int(std::floor(w.z())));
        }
    }
    EXPECT_EQ(stats.input_voxels, with_normal);
    EXPECT_EQ(cloud.points.size(), cells.size());
    EXPECT_LT(cloud.points.size(), with_normal);  // the maps overlap: some voxels were fused
    ASSERT_EQ(cloud.normals.size(), cloud.points.size());
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
        EXPECT_NEAR(cloud.normals[i].norm(), 1.0f, 1e-4f);
    }
}

TEST(GlobalMap, MovingAnAnchorMovesItsVoxels) {
    const common::LocalMapData m = scene_map(0, registration::test::xy_yaw(1, 2, 10));
    std::vector<PlacedLocalMap> placed(1);
    placed[0].map = &m;
    placed[0].T_world_anchor = m.T_odom_anchor;
    const common::PlyCloud before = build_global_map(placed, GlobalMapConfig());
    // Corrected anchor: 90 deg about z and 5 m up (whole cells, so no cell is split or merged).
    Eigen::Isometry3d correction = registration::test::xy_yaw(0, 0, 90);
    correction.translation().z() = 5.0;
    placed[0].T_world_anchor = correction * m.T_odom_anchor;
    const common::PlyCloud after = build_global_map(placed, GlobalMapConfig());
    ASSERT_EQ(after.points.size(), before.points.size());
    for (std::size_t i = 0; i < before.points.size(); ++i) {
        EXPECT_LT((after.points[i] - (correction.cast<float>() * before.points[i])).norm(), 1e-3f);
        EXPECT_LT((after.normals[i] - correction.linear().cast<float>() * before.normals[i]).norm(),
                  1e-4f);
    }
}

TEST(GlobalMap, FiltersAndValidation) {
    common::LocalMapData m;
    m.voxel_size = 1.0f;
    common::VoxelData v;
    v.centre = Eigen::Vector3f(0.5f, 0.5f, 0.5f);
    v.point_count = 1;
    m.voxels.push_back(v);  // no normal
    v.index = Eigen::Vector3i(1, 0, 0);
    v.centre = Eigen::Vector3f(1.5f, 0.5f, 0.5f);
    v.normal = Eigen::Vector3f::UnitZ();
    v.point_count = 3;
    v.planarity = 0.9f;
    m.voxels.push_back(v);
    std::vector<PlacedLocalMap> placed(1);
    placed[0].map = &m;
    EXPECT_EQ(build_global_map(placed, GlobalMapConfig()).points.size(), 1u);
    GlobalMapConfig all;
    all.with_normal_only = false;
    EXPECT_EQ(build_global_map(placed, all).points.size(), 2u);
    all.min_point_count = 5;
    EXPECT_EQ(build_global_map(placed, all).points.size(), 0u);
    GlobalMapConfig bad;
    bad.min_planarity = 2.0;
    ASSERT_TRUE(validate(bad));
    EXPECT_EQ(validate(bad)->key, "min_planarity");
    EXPECT_EQ(validate(bad)->problem, "must be in [0, 1] (got 2)");
    EXPECT_FALSE(validate(GlobalMapConfig()));
}

}  // namespace
}  // namespace ltm::map
