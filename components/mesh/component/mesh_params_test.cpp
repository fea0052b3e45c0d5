#include "mesh/component/mesh_params.hpp"

#include <gtest/gtest.h>

namespace ltm::mesh {
namespace {

runtime::Parameters params_of(const std::string& yaml) {
    return runtime::Parameters(YAML::Load(yaml), "test.yaml", "mesh");
}

std::string error_of(const std::string& yaml) {
    try {
        runtime::Parameters p = params_of(yaml);
        load_mesh_params(p);
        p.check_all_used();
    } catch (const runtime::ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(MeshParams, DefaultsThenOverrides) {
    runtime::Parameters none = params_of("{}");
    const MeshComponentConfig d = load_mesh_params(none);
    EXPECT_NO_THROW(none.check_all_used());
    EXPECT_TRUE(d.mesh_file.empty());
    EXPECT_EQ(d.frame_id, "map");
    EXPECT_EQ(d.max_queue, 20);
    EXPECT_FALSE(d.skip_while_busy);
    const MeshConfig core;
    EXPECT_DOUBLE_EQ(d.mesh.grid_size, core.grid_size);
    EXPECT_DOUBLE_EQ(d.mesh.kernel, core.kernel);
    EXPECT_EQ(d.mesh.vertex_normals, core.vertex_normals);

    runtime::Parameters p = params_of(
        "mesh_file: /tmp/out/mesh.ply\nframe_id: site\nmax_queue: 3\nskip_while_busy: true\n"
        "grid_size: 0.1\ntruncation: 0.3\nmin_points: 5\nvertex_normals: false\n");
    const MeshComponentConfig c = load_mesh_params(p);
    EXPECT_NO_THROW(p.check_all_used());
    EXPECT_EQ(c.mesh_file, "/tmp/out/mesh.ply");
    EXPECT_EQ(c.frame_id, "site");
    EXPECT_EQ(c.max_queue, 3);
    EXPECT_TRUE(c.skip_while_busy);
    EXPECT_DOUBLE_EQ(c.mesh.grid_size, 0.1);
    EXPECT_DOUBLE_EQ(c.mesh.truncation, 0.3);
    EXPECT_EQ(c.mesh.min_points, 5);
    EXPECT_FALSE(c.mesh.vertex_normals);
    EXPECT_DOUBLE_EQ(c.mesh.support, core.support);  // untouched: the core's default
}

TEST(MeshParams, ABadParameterIsOneLineNamingFileLineAndKey) {
    EXPECT_EQ(error_of("max_queue: 0"), "test.yaml:1: mesh.max_queue: must be >= 1");
    EXPECT_EQ(error_of("a: 1\ngrid_size: fine"),
              "test.yaml:2: mesh.grid_size: expected a number, got 'fine'");
    EXPECT_EQ(error_of("grid_size: 0.1\ntruncation: 0.05"),
              "test.yaml:2: mesh.truncation: must be at least grid_size (or 0: 2 grid cells)");
    EXPECT_EQ(
        error_of("mesh_fille: x.ply").rfind("test.yaml:1: mesh.mesh_fille: unknown parameter", 0),
        0u)
        << error_of("mesh_fille: x.ply");
    for (const std::string bad : {"frame_id: ''", "skip_while_busy: maybe", "support: 100",
                                  "min_points: 0", "kernel: -1", "mesh_file: [a, b]"}) {
        const std::string e = error_of(bad);
        EXPECT_EQ(e.rfind("test.yaml:1: mesh.", 0), 0u) << bad << ": " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    }
}

}  // namespace
}  // namespace ltm::mesh
