// Chunks moved with their anchors, overlapping local maps sharing space, placement of chunks
// outside the graph.
#include "mesh/core/mesh_atlas.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh/core/test_surfaces.hpp"
#include "mesh/core/triangle_mesh.hpp"

namespace ltm::mesh {
namespace {

Eigen::Isometry3d pose(double x, double y, double z, double yaw_deg, double roll_deg = 0.0) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(roll_deg * M_PI / 180.0, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, z);
    return T;
}

// Voxels of a scene given in the world, expressed in a local map's grid frame.
std::vector<common::VoxelData> to_grid(std::vector<common::VoxelData> voxels,
                                       const Eigen::Isometry3d& T_grid_world, double s) {
    for (common::VoxelData& v : voxels) {
        const Eigen::Vector3d c = T_grid_world * v.centre.cast<double>();
        v.centre = c.cast<float>();
        v.normal = (T_grid_world.linear() * v.normal.cast<double>()).cast<float>();
        v.index = Eigen::Vector3i((c / s).array().floor().cast<int>());
    }
    return voxels;
}

double nearest(const common::PlyMesh& m, const Eigen::Vector3f& p) {
    double best = 1e300;
    for (const Eigen::Vector3f& v : m.vertices) best = std::min(best, double((v - p).norm()));
    return best;
}

TEST(MeshAtlas, MeshMovedWithItsAnchorEqualsTheMeshRebuiltAtTheNewPose) {
    const double s = 0.3;
    // A ball on a ground patch, seen in the world; the local map holds it in its grid frame.
    auto world = test::sphere_voxels({0.2, 0.1, 1.6}, 1.2, s);
    const auto ground =
        test::plane_voxels(Eigen::Vector3d::UnitZ(), 0.0, {-2, -2, -0.5}, {2, 2, 0.5}, s);
    world.insert(world.end(), ground.begin(), ground.end());
    const Eigen::Isometry3d T_odom_anchor = pose(10, -3, 0.2, 35);
    const Eigen::Isometry3d T_anchor_grid = pose(0.05, 0.1, 0, 3);
    const Eigen::Isometry3d T_grid_world = (T_odom_anchor * T_anchor_grid).inverse();
    MeshAtlas atlas;
    atlas.add(make_chunk(
        test::local_map(7, to_grid(world, T_grid_world, s), s, T_odom_anchor, T_anchor_grid),
        MeshConfig{}));
    atlas.update();
    const common::PlyMesh before = atlas.chunk(7)->mesh;

    // The graph moves the anchor (an optimisation after a loop): the chunk moves, unchanged.
    const Eigen::Isometry3d T_world_anchor = pose(9.4, -2.5, 0.3, 41, 2);
    atlas.set_graph({{7, T_world_anchor}});
    EXPECT_EQ(atlas.update(), std::vector<std::uint64_t>{7});
    EXPECT_EQ(atlas.chunk(7)->mesh.vertices, before.vertices);  // nothing re-integrated
    const common::PlyMesh moved = atlas.global_mesh();

    // Rebuilt: the same voxels, moved to the new pose in the world, meshed from scratch on a
    // lattice of the world.
    const Eigen::Isometry3d T_new_world = T_world_anchor * T_anchor_grid;
    const auto rebuilt_voxels = to_grid(to_grid(world, T_grid_world, s), T_new_world, s);
    const common::PlyMesh rebuilt = mesh_voxels(rebuilt_voxels, s, MeshConfig{});
    ASSERT_GT(moved.vertices.size(), 500u);
    ASSERT_GT(rebuilt.vertices.size(), 500u);
    // Same surface: every vertex of one near the other (within the grid's cell, 0.1 m), and the
    // same area.
    double worst = 0.0, sum = 0.0;
    for (const Eigen::Vector3f& v : moved.vertices) {
        const double d = nearest(rebuilt, v);
        worst = std::max(worst, d);
        sum += d;
    }
    for (const Eigen::Vector3f& v : rebuilt.vertices) worst = std::max(worst, nearest(moved, v));
    EXPECT_LT(worst, 0.2);  // the fringe of the ground patch falls on another lattice
    EXPECT_LT(sum / double(moved.vertices.size()), 0.05);
    // And both on the true surface, moved: the ball or the ground.
    const Eigen::Isometry3d T_new_old = T_new_world * T_grid_world;
    const Eigen::Vector3d ball = T_new_old * Eigen::Vector3d(0.2, 0.1, 1.6);
    const Eigen::Vector3d up = T_new_old.linear() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d on_ground = T_new_old.translation();
    for (const common::PlyMesh* m : {&moved, &rebuilt})
        for (const Eigen::Vector3f& v : m->vertices) {
            const Eigen::Vector3d p = v.cast<double>();
            const double e =
                std::min(std::abs((p - ball).norm() - 1.2), std::abs(up.dot(p - on_ground)));
            ASSERT_LT(e, 0.06) << p.transpose();
        }
    EXPECT_NEAR(surface_area(moved), surface_area(rebuilt), 0.03 * surface_area(rebuilt));
}

// A wall x = 5 seen by two local maps, placed apart along it.
struct TwoMaps {
    MeshAtlas atlas;
    double s = 0.5;
    bool prepared = false;  // chunks meshed by the atlas (their owned places) instead of whole
    void add(std::uint64_t id, double y0, double y1, const Eigen::Isometry3d& T_world_anchor,
             double offset = 0.0) {
        auto wall = test::plane_voxels(-Eigen::Vector3d::UnitX(), -(5.0 + offset), {4, y0, 0},
                                       {6, y1, 3}, s);
        const common::LocalMapData m =
            test::local_map(id, to_grid(wall, T_world_anchor.inverse(), s), s, T_world_anchor);
        atlas.add(prepared ? prepare_chunk(m, MeshConfig{}) : make_chunk(m, MeshConfig{}));
    }
    int layers(double y, double z) const {
        return test::crossings(atlas.global_mesh(), {0.0, y, z}, {10.0, y + 0.001, z + 0.002});
    }
};

TEST(MeshAtlas, OverlappingLocalMapsGiveOneSurface) {
    TwoMaps w;
    w.add(1, -10, 15, pose(0, 0, 0, 0));
    w.add(2, 5, 30, pose(0, 20, 0, 90), 0.03);  // 3 cm of drift between the two maps
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 20, 0, 90)}});
    const auto changed = w.atlas.update();
    EXPECT_EQ(changed.size(), 2u);
    double sum = 0.0;
    for (const std::uint64_t id : w.atlas.ids()) sum += surface_area(w.atlas.chunk(id)->mesh);
    const double area = surface_area(w.atlas.global_mesh());
    EXPECT_GT(sum, 1.25 * 120.0);  // the chunks overlap over 10 m of the 40 m wall
    EXPECT_NEAR(area, 120.0, 0.1 * 120.0);
    for (const double y : {-8.3, -2.1, 3.7, 6.2, 8.9, 11.3, 13.6, 17.2, 24.4, 28.8})
        for (const double z : {0.73, 1.61, 2.37}) EXPECT_EQ(w.layers(y, z), 1) << y << " " << z;
    // Nothing changes when nothing moved; moving one anchor changes both (their seam).
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 20, 0, 90)}});
    EXPECT_TRUE(w.atlas.update().empty());
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 19, 0, 90)}});
    EXPECT_EQ(w.atlas.update().size(), 2u);
}

TEST(MeshAtlas, PreparedChunksMeshOnlyWhatTheyOwnAndMeshMoreWhenTheyComeToOwnMore) {
    TwoMaps w;
    w.prepared = true;
    w.add(1, -10, 15, pose(0, 0, 0, 0));
    w.add(2, 5, 30, pose(0, 20, 0, 90), 0.03);
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 20, 0, 90)}});
    EXPECT_EQ(w.atlas.update().size(), 2u);
    EXPECT_EQ(w.atlas.totals().meshings, 2u);
    double sum = 0.0;
    for (const std::uint64_t id : w.atlas.ids()) sum += surface_area(w.atlas.chunk(id)->mesh);
    EXPECT_LT(sum, 1.15 * 120.0);  // the overlap meshed about once, not twice
    EXPECT_NEAR(surface_area(w.atlas.global_mesh()), 120.0, 0.1 * 120.0);
    for (const double y : {-8.3, 3.7, 8.9, 11.3, 13.6, 24.4})
        for (const double z : {0.73, 2.37}) EXPECT_EQ(w.layers(y, z), 1) << y << " " << z;
    // A small correction (0.3 m): whoever meshes a place now, it has one surface (but within a
    // triangle of the seam, y = 10.15, where the two lattices' triangles may overlap or miss by
    // one triangle).
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 20.3, 0, 90)}});
    w.atlas.update();
    for (const double y : {-8.3, 3.7, 8.9, 9.8, 10.5, 11.3, 13.6, 24.4})
        for (const double z : {0.73, 2.37}) EXPECT_EQ(w.layers(y, z), 1) << y << " " << z;
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 20, 0, 90)}});
    w.atlas.update();
    const std::size_t before = w.atlas.totals().meshings;
    // Map 2 moves 6 m along the wall (a loop closure): each map now owns places of its own it
    // did not mesh (the seam moved in both their frames) and meshes them again from its own
    // voxels; still one surface everywhere.
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 26, 0, 90)}});
    w.atlas.update();
    EXPECT_EQ(w.atlas.totals().meshings, before + 2);
    for (const double y : {-8.3, 3.7, 8.9, 11.3, 13.6})
        for (const double z : {0.73, 2.37}) EXPECT_EQ(w.layers(y, z), 1) << y << " " << z;
    // Nothing moves: nothing is meshed again.
    w.atlas.update();
    EXPECT_EQ(w.atlas.totals().meshings, before + 2);
}

TEST(MeshAtlas, ChunksAddedOneByOneOwnWhatTheyOwnWhenAddedTogether) {
    // New neighbours only take places away: adding chunks one update at a time gives what one
    // update over all of them gives, triangle for triangle.
    TwoMaps one, all;
    const std::map<std::uint64_t, Eigen::Isometry3d> graph = {
        {1, pose(0, 0, 0, 0)}, {2, pose(0, 20, 0, 90)}, {3, pose(1, 9, 0, 30)}};
    auto add = [&](TwoMaps& w, std::uint64_t id) {
        const double y0[] = {0, -10, 5, -2}, y1[] = {0, 15, 30, 22};
        w.add(id, y0[id], y1[id], graph.at(id), 0.01 * double(id));
    };
    for (const std::uint64_t id : {1, 2, 3}) {
        add(one, id);
        std::map<std::uint64_t, Eigen::Isometry3d> g;
        for (std::uint64_t k = 1; k <= id; ++k) g[k] = graph.at(k);
        one.atlas.set_graph(g);
        one.atlas.update();
    }
    for (const std::uint64_t id : {1, 2, 3}) add(all, id);
    all.atlas.set_graph(graph);
    all.atlas.update();
    for (const std::uint64_t id : {1, 2, 3}) {
        const common::PlyMesh a = one.atlas.owned_mesh(id), b = all.atlas.owned_mesh(id);
        EXPECT_GT(a.triangles.size(), 0u) << id;
        EXPECT_EQ(a.triangles, b.triangles) << id;
        EXPECT_EQ(a.vertices, b.vertices) << id;
    }
    // Each of the first two gave places to a later one.
    for (const std::uint64_t id : {1, 2})
        EXPECT_LT(one.atlas.owned_mesh(id).triangles.size(),
                  one.atlas.chunk(id)->mesh.triangles.size())
            << id;
}

TEST(MeshAtlas, APlaceOnlyTheFartherMapSawStaysWithIt) {
    TwoMaps w;
    w.add(1, -10, 2, pose(0, 0, 0, 0));
    w.add(2, -10, 30, pose(0, 14, 0, 0));
    w.atlas.set_graph({{1, pose(0, 0, 0, 0)}, {2, pose(0, 14, 0, 0)}});
    w.atlas.update();
    for (const double y : {-8.3, -2.1, 0.7, 4.3, 5.9, 12.2, 25.1})
        for (const double z : {0.73, 2.37}) EXPECT_EQ(w.layers(y, z), 1) << y << " " << z;
    EXPECT_NEAR(surface_area(w.atlas.global_mesh()), 120.0, 0.1 * 120.0);
}

TEST(MeshAtlas, ChunksOutsideTheGraphFollowTheirSegmentsCorrection) {
    MeshAtlas atlas;
    const auto wall = test::plane_voxels(Eigen::Vector3d::UnitX(), 0.0, {-1, 0, 0}, {1, 2, 2}, 0.5);
    auto chunk = [&](std::uint64_t id, std::uint32_t segment, const Eigen::Isometry3d& T_odom) {
        common::LocalMapData m = test::local_map(id, wall, 0.5, T_odom);
        m.segment = segment;
        atlas.add(make_chunk(m, MeshConfig{}));
    };
    chunk(1, 0, pose(0, 0, 0, 0));
    chunk(2, 0, pose(20, 0, 0, 10));  // folded into another map: not a graph node
    chunk(3, 1, pose(50, 0, 0, 0));   // a segment with no graph node yet
    const Eigen::Isometry3d G1 = pose(1, 2, 0, 5);
    atlas.set_graph({{1, G1}});
    atlas.update();
    EXPECT_TRUE(atlas.T_world_anchor(1).isApprox(G1));
    EXPECT_TRUE(atlas.T_world_anchor(2).isApprox(G1 * pose(20, 0, 0, 10)));
    EXPECT_TRUE(atlas.T_world_anchor(3).isApprox(pose(50, 0, 0, 0)));
    EXPECT_FALSE(atlas.in_graph(2));
    // A newer revision replaces a chunk, an older one is ignored.
    common::LocalMapData m = test::local_map(2, wall, 0.5, pose(20, 0, 0, 10));
    m.revision = 1;
    EXPECT_FALSE(atlas.add(make_chunk(m, MeshConfig{})));
    m.revision = 2;
    EXPECT_TRUE(atlas.add(make_chunk(m, MeshConfig{})));
    EXPECT_TRUE(atlas.remove(3));
    EXPECT_FALSE(atlas.remove(3));
    atlas.update();
    EXPECT_EQ(atlas.ids(), (std::vector<std::uint64_t>{1, 2}));
}

}  // namespace
}  // namespace ltm::mesh
