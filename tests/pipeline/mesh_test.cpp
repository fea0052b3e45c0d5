// The mesh component through the host: the tiny simulated loop through odometry (a new local map
// every 5 m) and mapping; the mesh component meshes the finished local maps. While the mission
// runs, `./ltm map mesh`'s request writes the mesh where it asks and a late-joining reader gets
// the chunks; at shutdown the global mesh is written. Both files are opened by an independent
// reader (PCL) and hold what the component says. A bad parameter is one line.
#include <gtest/gtest.h>
#include <pcl/PolygonMesh.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <regex>
#include <thread>

#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;

namespace {

const std::string kScenario = ltm::tests::scenario("tiny_loop.yaml");

std::string header(int domain) {
    return "domain_id: " + std::to_string(domain) + "\ndds: " + ltm::tests::kLoopbackDds +
           "\nnamespace: /robot\n";
}

struct Counts {
    long vertices = -1, triangles = -1;
};

// What the component says it wrote to `file`: "mesh written to FILE: V vertices, T triangles".
Counts said(const std::string& log, const std::string& file) {
    std::smatch m;
    const std::regex line("mesh written to " + std::regex_replace(file, std::regex("[.]"), "[.]") +
                          ": ([0-9]+) vertices, ([0-9]+) triangles");
    if (!std::regex_search(log, m, line)) return {};
    return {std::stol(m[1]), std::stol(m[2])};
}

// What PCL reads from the file.
Counts read_by_pcl(const std::string& file) {
    pcl::PolygonMesh mesh;
    if (pcl::io::loadPLYFile(file, mesh) != 0) return {};
    for (const pcl::Vertices& v : mesh.polygons)
        if (v.vertices.size() != 3) return {};
    return {long(mesh.cloud.width) * long(mesh.cloud.height), long(mesh.polygons.size())};
}

class MeshPipeline : public ltm::tests::TempDirTest {
  protected:
    MeshPipeline() : TempDirTest("ltm_mesh_pipeline_") {}
};

}  // namespace

TEST_F(MeshPipeline, WritesTheMeshAtShutdownAndOnRequestAndLateReadersGetTheChunks) {
    const std::string mesh_file = path("out/mesh.ply");  // its folder created at the write
    // The mission keeps running when the sensor is done, until it is told to stop.
    const std::string mission = write("mission.yaml", header(227) + R"(topics: {points: stream}
exit_when_sources_done: false
shutdown_timeout_s: 60
components:
  - name: sensor
    type: simulator
    params: {scenario: )" + kScenario + R"(, mode: fast}
  - name: odometry
    type: odometry
    params: {preset: vlp16, local_map: {switch_distance: 5}}
  - name: mapping
    type: mapping
    params: {preset: vlp16}
  - name: mesh
    type: mesh
    params: {mesh_file: )" + mesh_file + R"(}
)");
    Process host({kHost, mission}, path("mission"));
    ASSERT_TRUE(host.wait_for_log(" triangles owned; ", 120)) << host.err();

    // `./ltm map mesh --mesh-file requested.ply` while it runs.
    const std::string requested = path("requested.ply");
    const std::string request = write("request.yaml", header(227) + R"(components:
  - name: map_request
    type: map_request
    params: {command: mesh, mesh_file: )" + requested + R"(}
)");
    Process requester({kHost, request}, path("request"));
    ASSERT_EQ(requester.wait(60), 0) << requester.err() << host.err();
    EXPECT_NE(requester.err().find("mesh written to " + requested), std::string::npos)
        << requester.err();
    // The mapping component leaves the mesh's request alone (no "unknown command" answer).
    EXPECT_EQ(host.err().find("unknown command"), std::string::npos) << host.err();
    const Counts answered = said(host.err(), requested);
    EXPECT_GT(answered.triangles, 0) << host.err();
    const Counts on_disk = read_by_pcl(requested);
    EXPECT_EQ(on_disk.vertices, answered.vertices);
    EXPECT_EQ(on_disk.triangles, answered.triangles);

    // A reader joining late gets the chunks published so far (the mesh topic keeps them).
    const std::string late = write("late.yaml", header(227) + R"(idle_exit_s: 3
components:
  - name: chunks
    type: cloud_writer
    params: {dir: )" + path("chunks") + R"(, inputs: [mesh]}
)");
    Process reader({kHost, late}, path("late"));
    ASSERT_EQ(reader.wait(60), 0) << reader.err();
    std::size_t chunks = 0;
    for (const auto& e : fs::directory_iterator(path("chunks")))
        chunks += e.path().filename().string().rfind("mesh_", 0) == 0;
    EXPECT_GE(chunks, 1u) << reader.err();

    // Stopped: the maps still waiting are meshed, the global mesh written.
    host.signal(SIGINT);
    ASSERT_EQ(host.wait(120), 0) << host.err();
    const Counts final_said = said(host.err(), mesh_file);
    EXPECT_GE(final_said.triangles, answered.triangles) << host.err();
    const Counts final_read = read_by_pcl(mesh_file);
    EXPECT_EQ(final_read.vertices, final_said.vertices);
    EXPECT_EQ(final_read.triangles, final_said.triangles);
    EXPECT_EQ(host.err().find("mesh_failed"), std::string::npos) << host.err();
}

// A request with nowhere to write is answered as failed, in one line.
TEST_F(MeshPipeline, ARequestWithNowhereToWriteFails) {
    const std::string cfg = write("nowhere.yaml", header(228) + R"(components:
  - name: mesh
    type: mesh
  - name: map_request
    type: map_request
    params: {command: mesh}
)");
    Process host({kHost, cfg}, path("host"));
    EXPECT_EQ(host.wait(60), 1) << host.err();
    EXPECT_NE(host.err().find("nowhere to write: no mesh file in the request or the component's "
                              "mesh_file"),
              std::string::npos)
        << host.err();
}

// A bad parameter stops the host before it starts, with one line naming the file, line and key.
TEST_F(MeshPipeline, BadParameterIsOneLine) {
    const std::string cfg = write("bad.yaml", header(229) + R"(components:
  - name: mesh
    type: mesh
    params: {grid_size: 0.1, truncation: 0.01}
)");
    Process host({kHost, cfg}, path("host"));
    EXPECT_EQ(host.wait(30), 2);
    const std::string err = host.err();
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(cfg + ":7: mesh.truncation: must be at least grid_size"), std::string::npos)
        << err;
}

// The mesh request names its file with mesh_file; the mapping's keys are refused with it (and
// mesh_file with the mapping's commands), in one line.
TEST_F(MeshPipeline, AMeshRequestTakesOnlyAMeshFile) {
    const auto refused = [&](const std::string& params) {
        const std::string cfg = write("request.yaml", header(230) + R"(components:
  - name: map_request
    type: map_request
    params: )" + params + "\n");
        Process host({kHost, cfg, "--check"}, path("host"));
        EXPECT_EQ(host.wait(30), 2) << params;
        const std::string err = host.err();
        EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
        return err;
    };
    EXPECT_NE(refused("{command: mesh, global_map_file: " + path("g.ply") + "}")
                  .find(":7: map_request.global_map_file: not with command mesh (its file: "
                        "mesh_file)"),
              std::string::npos);
    EXPECT_NE(refused("{command: global_map, mesh_file: " + path("m.ply") + "}")
                  .find(":7: map_request.mesh_file: only with command mesh"),
              std::string::npos);
}
