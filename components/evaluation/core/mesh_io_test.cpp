#include "evaluation/core/mesh_io.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "common/core/io_error.hpp"

namespace ltm::eval {
namespace {

TEST(MeshIo, ReadsWhatCommonWrites) {
    common::PlyMesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5f}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    const std::string path = testing::TempDir() + "ltm_eval_mesh_io.ply";
    common::write_ply(path, m);
    const common::PlyMesh r = read_mesh_file(path);
    ASSERT_EQ(r.vertices.size(), 4u);
    EXPECT_TRUE(r.vertices[2].isApprox(Eigen::Vector3f(1, 1, 0.5f)));
    EXPECT_EQ(r.triangles, m.triangles);
}

TEST(MeshIo, SplitsPolygonsIntoFans) {
    const std::string path = testing::TempDir() + "ltm_eval_mesh_io_quad.ply";
    std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                           "property float y\nproperty float z\nelement face 1\n"
                           "property list uchar int vertex_indices\nend_header\n"
                           "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    const common::PlyMesh r = read_mesh_file(path);
    ASSERT_EQ(r.triangles.size(), 2u);
    EXPECT_EQ(r.triangles[1], Eigen::Vector3i(0, 2, 3));
}

TEST(MeshIo, RejectsMissingAndNonPlyFiles) {
    EXPECT_THROW(read_mesh_file("/nonexistent/mesh.ply"), common::IoError);
    const std::string obj = testing::TempDir() + "ltm_eval_mesh_io.obj";
    std::ofstream(obj) << "v 0 0 0\n";
    EXPECT_THROW(read_mesh_file(obj), common::IoError);
    const std::string junk = testing::TempDir() + "ltm_eval_mesh_io_junk.ply";
    std::ofstream(junk) << "not a ply\n";
    EXPECT_THROW(read_mesh_file(junk), common::IoError);
}

}  // namespace
}  // namespace ltm::eval
