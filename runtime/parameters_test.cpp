#include "runtime/parameters.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <functional>

using namespace ltm::runtime;

namespace {

Parameters make(const char* yaml) { return Parameters(YAML::Load(yaml), "test.yaml", "comp"); }

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Parameters, TypedValuesAndDefaults) {
    Parameters p =
        make("rate: 2.5\ncount: 3\nname: abc\nflag: true\nlist: [1, 2.5]\ngroup:\n  size: 0.5\n");
    EXPECT_DOUBLE_EQ(p.get<double>("rate", 1.0), 2.5);
    EXPECT_EQ(p.get<int>("count", 0), 3);
    EXPECT_EQ(p.get<std::string>("name", ""), "abc");
    EXPECT_TRUE(p.get<bool>("flag", false));
    EXPECT_EQ(p.get<std::vector<double>>("list", {}), (std::vector<double>{1, 2.5}));
    EXPECT_DOUBLE_EQ(p.get<double>("group.size", 0), 0.5);
    EXPECT_EQ(p.get<int>("absent", 7), 7);
    EXPECT_NO_THROW(p.check_all_used());
}

TEST(Parameters, IllTypedValueNamesFileLineAndKey) {
    Parameters p = make("a: 1\nrate: fast\n");
    p.get<int>("a", 0);
    EXPECT_EQ(error_of([&] { p.get<double>("rate", 1.0); }),
              "test.yaml:2: comp.rate: expected a number, got 'fast'");
    Parameters q = make("n: 2.5\n");
    EXPECT_EQ(error_of([&] { q.get<int>("n", 0); }),
              "test.yaml:1: comp.n: expected an integer, got '2.5'");
    Parameters r = make("n: -1\n");
    EXPECT_NE(error_of([&] { r.get<unsigned>("n", 0u); }).find("expected a non-negative integer"),
              std::string::npos);
    Parameters s = make("s: [1, 2]\n");
    EXPECT_EQ(error_of([&] { s.get<std::string>("s", ""); }),
              "test.yaml:1: comp.s: expected a string");
}

TEST(Parameters, UnknownKeysAreRejectedWithTheirLine) {
    Parameters p = make("rate: 1\ngroup:\n  size: 2\n  sise: 3\n");
    p.get<double>("rate", 0);
    p.get<double>("group.size", 0);
    const std::string e = error_of([&] { p.check_all_used(); });
    EXPECT_EQ(e, "test.yaml:4: comp.group.sise: unknown parameter (known: group.size, rate)");
}

TEST(Parameters, ManyKnownKeysNameTheClosestOnes) {
    Parameters p = make("scan_context: {rigns: 3}\n");
    for (const char* k :
         {"scan_context.rings", "scan_context.sectors", "scan_context.kind", "pose_graph.loop_loss",
          "pose_graph.max_iterations", "loop_edge.sigma_rotation", "loop_edge.sigma_translation",
          "frame_id", "map_dir", "global_map_file", "load_map_dir", "save_period_s", "preset"})
        p.get<std::string>(k, "");
    EXPECT_EQ(error_of([&] { p.check_all_used(); }),
              "test.yaml:1: comp.scan_context.rigns: unknown parameter (closest of 13 known: "
              "scan_context.rings, "
              "scan_context.kind, scan_context.sectors)");
}

TEST(Parameters, RequiredAndPaths) {
    Parameters p = make("file: /definitely/not/here.txt\ndir: /tmp\n");
    EXPECT_EQ(error_of([&] { p.require<double>("rate"); }),
              "test.yaml:1: comp.rate: required parameter is missing");
    EXPECT_EQ(error_of([&] { p.path("file", "", PathCheck::kFileExists); }),
              "test.yaml:1: comp.file: no such file: /definitely/not/here.txt");
    EXPECT_EQ(p.path("dir", "", PathCheck::kDirExists), "/tmp");
}

TEST(Parameters, EnvironmentExpansion) {
    setenv("LTM_TEST_VAR", "/data", 1);
    unsetenv("LTM_TEST_UNSET");
    EXPECT_EQ(expand_env("${LTM_TEST_VAR}/x"), "/data/x");
    EXPECT_EQ(expand_env("${LTM_TEST_UNSET:-fallback}/y"), "fallback/y");
    EXPECT_EQ(expand_env("plain"), "plain");
    Parameters p = make("out: ${LTM_TEST_VAR}/out\n");
    EXPECT_EQ(p.get<std::string>("out", ""), "/data/out");
}

TEST(Parameters, LookupsNeverAddKeys) {
    YAML::Node n = YAML::Load("a: 1\n");
    Parameters p(n, "f", "c");
    p.get<int>("b.c.d", 0);
    EXPECT_FALSE(p.has("b"));
    EXPECT_EQ(n.size(), 1u);
}

TEST(Parameters, FromFile) {
    const std::string path =
        ::testing::TempDir() + "params_" + std::to_string(::getpid()) + ".yaml";
    { std::ofstream(path) << "voxel_size: 0.5\nbad: [\n"; }
    EXPECT_NE(error_of([&] { Parameters::from_file(path, "odometry"); }).find(":3: odometry: "),
              std::string::npos);
    { std::ofstream(path) << "voxel_size: 0.5\n"; }
    Parameters p = Parameters::from_file(path, "odometry");
    EXPECT_DOUBLE_EQ(p.get<double>("voxel_size", 1.0), 0.5);
    EXPECT_EQ(error_of([&] { Parameters::from_file("/no/such.yaml", "odometry"); }),
              "/no/such.yaml:0: odometry: no such file");
}

TEST(Parameters, DottedKeysAreTheSameParameterAsNestedOnes) {
    // `keyframe.distance: 0.3` used to pass the unknown-key check yet read as absent.
    Parameters p = make("rate: 1\nkeyframe.distance: 0.3\ngroup:\n  inner.size: 4\n");
    EXPECT_DOUBLE_EQ(p.get<double>("keyframe.distance", 1.0), 0.3);
    EXPECT_DOUBLE_EQ(p.get<double>("group.inner.size", 0.0), 4.0);
    EXPECT_TRUE(p.has("keyframe.distance"));
    EXPECT_FALSE(p.has("keyframe.angle"));
    p.get<double>("rate", 0);
    EXPECT_NO_THROW(p.check_all_used());
    EXPECT_EQ(error_of([&] { p.get<int>("keyframe.distance", 0); }),
              "test.yaml:2: comp.keyframe.distance: expected an integer, got '0.3'");
    Parameters both = make("keyframe.distance: 0.3\nkeyframe:\n  distance: 0.5\n");
    both.get<double>("keyframe.distance", 1.0);
    EXPECT_NE(error_of([&] { both.check_all_used(); }).find("given twice"), std::string::npos);
}
