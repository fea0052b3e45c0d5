// A chunk through ltm_msgs/Mesh and back (in memory and through Cyclone DDS), bad chunks, local
// maps and pose graphs refused in one line.
#include "mesh/component/mesh_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mesh/core/test_surfaces.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/local_map.hpp"
#include "runtime/convert/pose_graph.hpp"
#include "runtime/testing/dds_loopback.hpp"

namespace ltm::mesh {
namespace {

const float kNan = std::numeric_limits<float>::quiet_NaN();

Eigen::Isometry3d pose(double x, double y, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0.3);
    return T;
}

// Two local maps of one wall, overlapping: each owns part of it.
MeshAtlas two_chunks() {
    const double s = 0.3;
    const auto wall =
        test::plane_voxels(Eigen::Vector3d::UnitX(), 4.0, {3.5, -6, -1}, {4.5, 6, 2}, s);
    MeshAtlas atlas;
    atlas.add(make_chunk(test::local_map(1, wall, s, Eigen::Isometry3d::Identity()), {}));
    // The second map's grid frame is the world moved by its anchor.
    const Eigen::Isometry3d T = pose(0, 3, 0);
    std::vector<common::VoxelData> moved = wall;
    for (common::VoxelData& v : moved)
        v.centre = (T.inverse() * v.centre.cast<double>()).cast<float>();
    atlas.add(make_chunk(test::local_map(2, moved, s, T), {}));
    atlas.set_graph({{1, pose(0.1, 0, 0.01)}, {2, pose(0.1, 3, 0.01)}});
    atlas.update();
    return atlas;
}

void expect_same(const PlacedMesh& a, const PlacedMesh& b) {
    EXPECT_EQ(a.local_map_id, b.local_map_id);
    EXPECT_EQ(a.revision, b.revision);
    EXPECT_TRUE(a.T_map_anchor.isApprox(b.T_map_anchor, 1e-12));
    EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
    EXPECT_EQ(a.mesh.normals, b.mesh.normals);
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
}

std::string refusal(const msg::Mesh& m) {
    try {
        from_msg(m);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

TEST(MeshMessages, AnAtlasChunkRoundTrips) {
    const MeshAtlas atlas = two_chunks();
    for (const std::uint64_t id : {1u, 2u}) {
        const PlacedMesh p = placed_chunk(atlas, id);
        // The owned part (the overlap went to one of the two), with its normals, where it is.
        EXPECT_GT(p.mesh.triangles.size(), 10u);
        EXPECT_LT(p.mesh.triangles.size(), atlas.chunk(id)->mesh.triangles.size());
        EXPECT_EQ(p.mesh.normals.size(), p.mesh.vertices.size());
        EXPECT_TRUE(p.T_map_anchor.isApprox(atlas.T_world_anchor(id)));
        const convert::Owned<msg::Mesh> m = to_msg(p, {12, 500}, "map");
        EXPECT_EQ(convert::to_string(m->header.frame_id), "map");
        EXPECT_EQ(m->header.stamp.sec, 12);
        EXPECT_EQ(m->vertices._length, 3 * p.mesh.vertices.size());
        EXPECT_EQ(m->triangles._length, 3 * p.mesh.triangles.size());
        expect_same(p, from_msg(*m));
    }
    // Without normals: an empty sequence, and back.
    PlacedMesh p = placed_chunk(atlas, 1);
    p.mesh.normals.clear();
    p.revision = 9;
    expect_same(p, from_msg(*to_msg(p, {}, "map")));
}

TEST(MeshMessages, ABadChunkIsRefusedInOneLine) {
    PlacedMesh p;
    p.local_map_id = 5;
    p.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    p.mesh.triangles = {{0, 1, 2}};
    convert::Owned<msg::Mesh> m = to_msg(p, {}, "map");
    EXPECT_EQ(refusal(*m), "");
    m->triangles._buffer[2] = 3;
    EXPECT_EQ(refusal(*m), "mesh chunk 5: triangle 0 names vertex 3 of 3");
    m->triangles._buffer[2] = 2;
    m->triangles._length = 2;
    EXPECT_EQ(refusal(*m), "mesh chunk 5: 2 triangle indices, not triples");
    m->triangles._length = 3;
    m->vertices._length = 8;
    EXPECT_EQ(refusal(*m), "mesh chunk 5: 8 vertex coordinates, not x y z triples");
    m->vertices._length = 6;
    EXPECT_EQ(refusal(*m), "mesh chunk 5: 3 normals for 2 vertices");
    m->vertices._length = 9;
    m->vertices._buffer[4] = kNan;
    EXPECT_EQ(refusal(*m), "mesh chunk 5: vertex 1 is not finite");
    m->vertices._buffer[4] = 0;
    m->normals._buffer[8] = std::numeric_limits<float>::infinity();
    EXPECT_EQ(refusal(*m), "mesh chunk 5: normal 2 is not finite");
    m->normals._buffer[8] = 1;
    m->anchor.position.y = std::nan("");
    EXPECT_EQ(refusal(*m), "mesh chunk 5: anchor pose not finite");
    // A zeroed message (no sequences at all) is an empty chunk.
    const msg::Mesh empty{};
    EXPECT_EQ(from_msg(empty).mesh.vertices.size(), 0u);
}

TEST(MeshMessages, LocalMapsAndGraphsAreChecked) {
    common::LocalMapData map = test::local_map(
        4, test::plane_voxels(Eigen::Vector3d::UnitZ(), 0, {-1, -1, -1}, {1, 1, 1}, 0.5), 0.5,
        pose(1, 2, 0.5));
    map.voxels[0].centre.x() = kNan;  // the mesher leaves it out
    convert::LocalMapBuilder builder;
    const common::LocalMapData back = local_map_from_msg(builder.build(map, 3.0, "odom"));
    EXPECT_EQ(back.id, 4u);
    EXPECT_EQ(back.voxels.size(), map.voxels.size());
    EXPECT_TRUE(back.T_odom_anchor.isApprox(map.T_odom_anchor));
    const auto refused = [&](const common::LocalMapData& d) {
        try {
            local_map_from_msg(builder.build(d, 3.0, "odom"));
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    common::LocalMapData bad = map;
    bad.voxel_size = 0;
    EXPECT_EQ(refused(bad), "local map 4: voxel size 0.000000 is not a positive number");
    bad.voxel_size = kNan;
    EXPECT_EQ(refused(bad).rfind("local map 4: voxel size ", 0), 0u);
    bad = map;
    bad.T_odom_anchor.translation().z() = kNan;
    EXPECT_EQ(refused(bad), "local map 4: anchor pose not finite");
    bad = map;
    bad.T_anchor_grid.translation().x() = kNan;
    EXPECT_EQ(refused(bad), "local map 4: grid pose not finite");

    convert::PoseGraphData g;
    g.revision = 7;
    g.anchors = {{1, pose(0, 0, 0)}, {3, pose(5, 1, 0.2)}};
    const auto anchors = anchors_from_msg(*convert::to_msg(g));
    ASSERT_EQ(anchors.size(), 2u);
    EXPECT_TRUE(anchors.at(3).isApprox(pose(5, 1, 0.2)));
    const auto graph_refused = [](const convert::PoseGraphData& d) {
        try {
            anchors_from_msg(*convert::to_msg(d));
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    g.anchors.push_back({1, pose(1, 0, 0)});
    EXPECT_EQ(graph_refused(g), "pose graph revision 7: anchor of local map 1: given twice");
    g.anchors.pop_back();
    g.anchors[1].T_map_anchor.translation().x() = std::nan("");
    EXPECT_EQ(graph_refused(g), "pose graph revision 7: anchor of local map 3: pose not finite");
}

// Serialised by Cyclone DDS and taken back by a reader of the same topic.
TEST(MeshMessages, RoundTripThroughDds) {
    const PlacedMesh p = placed_chunk(two_chunks(), 2);
    ASSERT_FALSE(p.mesh.triangles.empty());
    runtime::testing::DdsLoopback dds(226);
    dds.roundtrip<msg::Mesh>(*to_msg(p, {40, 7}, "map"), [&](const msg::Mesh& r) {
        EXPECT_EQ(convert::to_string(r.header.frame_id), "map");
        EXPECT_EQ(r.header.stamp.nanosec, 7u);
        expect_same(p, from_msg(r));
    });
}

}  // namespace
}  // namespace ltm::mesh
