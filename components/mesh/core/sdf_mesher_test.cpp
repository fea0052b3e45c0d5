// The signed distance of analytic surfaces from synthetic voxels, meshed and compared with the
// surface; the band's edge makes no surface; bad input.
#include "mesh/core/sdf_mesher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mesh/core/test_surfaces.hpp"
#include "mesh/core/triangle_mesh.hpp"

namespace ltm::mesh {
namespace {

TEST(SdfMesher, TiltedPlaneIsMeshedOnThePlaneFacingTheSensor) {
    const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
    const double offset = 0.37;
    const double s = 0.5;
    const auto voxels = test::plane_voxels(n, offset, {-5, -5, -3}, {5, 5, 3}, s);
    ASSERT_GT(voxels.size(), 300u);
    SdfStats stats;
    const common::PlyMesh mesh = mesh_voxels(voxels, s, MeshConfig{}, &stats);
    ASSERT_GT(mesh.triangles.size(), 1000u);
    EXPECT_EQ(stats.voxels_used, voxels.size());
    double worst = 0.0;
    for (const Eigen::Vector3f& v : mesh.vertices)
        worst = std::max(worst, std::abs(n.dot(v.cast<double>()) - offset));
    EXPECT_LT(worst, 0.005);  // a plane is exact (up to float and the grid's interpolation)
    // Every face looks towards the sensor's side.
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& i = mesh.triangles[t];
        const Eigen::Vector3f f = (mesh.vertices[i[1]] - mesh.vertices[i[0]])
                                      .cross(mesh.vertices[i[2]] - mesh.vertices[i[0]]);
        ASSERT_GT(f.cast<double>().dot(n), 0.0) << "triangle " << t;
    }
    ASSERT_EQ(mesh.normals.size(), mesh.vertices.size());
    // One layer: the patch's area is the plane's inside the box (10 x 10 m seen along n),
    // give or take the fringe (the support reaches a voxel beyond the last centres).
    const double area = surface_area(mesh);
    const double expected = 100.0 / n.z();
    EXPECT_GT(area, 0.85 * expected);
    EXPECT_LT(area, 1.15 * expected);
    // Nothing behind or in front of the plane: the band's edge (+-truncation) is not surfaced.
    const Eigen::Vector3d p0 = offset * n;
    EXPECT_EQ(test::crossings(mesh, p0 + 1.5 * n + Eigen::Vector3d(0.123, 0.0456, 0),
                              p0 - 1.5 * n + Eigen::Vector3d(0.123, 0.0456, 0)),
              1);
}

TEST(SdfMesher, SphereMeshedNearTheSphere) {
    const Eigen::Vector3d c(1.0, -2.0, 0.5);
    const double r = 3.0, s = 0.3;
    const auto voxels = test::sphere_voxels(c, r, s);
    const common::PlyMesh mesh = mesh_voxels(voxels, s, MeshConfig{});
    ASSERT_GT(mesh.triangles.size(), 1000u);
    double sum = 0.0, worst = 0.0;
    for (const Eigen::Vector3f& v : mesh.vertices) {
        const double e = std::abs((v.cast<double>() - c).norm() - r);
        sum += e;
        worst = std::max(worst, e);
    }
    // Planes through points of a curved surface: the sagitta of a voxel's patch (~1.5 cm here).
    EXPECT_LT(sum / double(mesh.vertices.size()), 0.02);
    EXPECT_LT(worst, 0.06);
    const double area = surface_area(mesh);
    EXPECT_NEAR(area, 4.0 * M_PI * r * r, 0.05 * 4.0 * M_PI * r * r);
    // Closed, outward faces: a segment from the centre out crosses once.
    EXPECT_EQ(test::crossings(mesh, c, c + Eigen::Vector3d(4.01, 0.333, 0.222)), 1);
    double outward = 0.0;
    for (const Eigen::Vector3i& i : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices[i[0]].cast<double>();
        const Eigen::Vector3d f =
            (mesh.vertices[i[1]].cast<double>() - a).cross(mesh.vertices[i[2]].cast<double>() - a);
        outward += f.dot(a - c) > 0.0 ? 1.0 : 0.0;
    }
    EXPECT_EQ(outward, double(mesh.triangles.size()));
}

TEST(SdfMesher, SurfaceEndsWhereItsVoxelsEnd) {
    const double s = 0.5;
    const auto voxels = test::plane_voxels(Eigen::Vector3d::UnitZ(), 0.1, {0, 0, -1}, {4, 3, 1}, s);
    MeshConfig config;
    const common::PlyMesh mesh = mesh_voxels(voxels, s, config);
    ASSERT_FALSE(mesh.triangles.empty());
    for (const Eigen::Vector3f& v : mesh.vertices) {
        ASSERT_GT(v.x(), -config.support * s - 1e-3);
        ASSERT_LT(v.x(), 4.0 + config.support * s + 1e-3);
        ASSERT_GT(v.y(), -config.support * s - 1e-3);
        ASSERT_LT(v.y(), 3.0 + config.support * s + 1e-3);
        ASSERT_NEAR(v.z(), 0.1, 0.005);
    }
}

TEST(SdfMesher, BadVoxelsAreLeftOutAndEmptyInputGivesAnEmptyMesh) {
    EXPECT_TRUE(mesh_voxels({}, 0.5, MeshConfig{}).triangles.empty());
    auto voxels = test::plane_voxels(Eigen::Vector3d::UnitZ(), 0.0, {0, 0, -1}, {3, 3, 1}, 0.5);
    const std::size_t good = voxels.size();
    common::VoxelData nan = voxels.front();
    nan.centre.x() = std::numeric_limits<float>::quiet_NaN();
    common::VoxelData no_normal = voxels.front();
    no_normal.normal.setZero();
    common::VoxelData inf_normal = voxels.front();
    inf_normal.normal.y() = std::numeric_limits<float>::infinity();
    common::VoxelData sparse = voxels.front();
    sparse.point_count = 1;
    voxels.insert(voxels.end(), {nan, no_normal, inf_normal, sparse});
    SdfStats stats;
    const common::PlyMesh mesh = mesh_voxels(voxels, 0.5, MeshConfig{}, &stats);
    EXPECT_EQ(stats.voxels_used, good);
    for (const Eigen::Vector3f& v : mesh.vertices) ASSERT_TRUE(v.allFinite());
    std::vector<common::VoxelData> only_bad = {nan, no_normal, inf_normal};
    EXPECT_TRUE(mesh_voxels(only_bad, 0.5, MeshConfig{}).triangles.empty());
}

TEST(SdfMesher, BadConfigIsOneLineNamingTheKey) {
    MeshConfig c;
    c.kernel = -1.0;
    try {
        mesh_voxels({}, 0.5, c);
        FAIL() << "no error";
    } catch (const common::ConfigError& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("mesh.kernel"), std::string::npos) << e.what();
    }
    EXPECT_THROW(mesh_voxels({}, 0.0, MeshConfig{}), common::ConfigError);
    EXPECT_THROW(mesh_voxels({}, std::nan(""), MeshConfig{}), common::ConfigError);
    c = MeshConfig{};
    c.grid_size = 0.2;
    c.truncation = 0.1;
    EXPECT_THROW(mesh_voxels({}, 0.5, c), common::ConfigError);
}

}  // namespace
}  // namespace ltm::mesh
