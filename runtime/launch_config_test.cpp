#include "runtime/launch_config.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "runtime/config_error.hpp"
#include "runtime/domain.hpp"

using namespace ltm::runtime;

namespace {

std::string write_temp(const std::string& text) {
    static int n = 0;
    const std::string path = ::testing::TempDir() + "launch_" + std::to_string(::getpid()) + "_" +
                             std::to_string(n++) + ".yaml";
    std::ofstream(path) << text;
    return path;
}

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
    const std::string path = write_temp(text);
    try {
        load_launch_config(path, overrides);
    } catch (const ConfigError& e) {
        std::string s = e.what();
        return s.substr(path.size());  // ":line: key: problem"
    }
    return "";
}

const char* kGood = R"(domain_id: 7
namespace: /robot
dds:
  interfaces: [lo]
  peers: [127.0.0.1]
  multicast: false
qos:
  stream: {depth: 3}
topics:
  points: stream
on_component_error: restart
components:
  - name: player
    type: kitti_player
    params:
      path: /data
      rate: 1.0
    remap:
      points: /kitti/points
  - type: trajectory_writer
)";

}  // namespace

TEST(LaunchConfig, ParsesEverySection) {
    const LaunchConfig c = load_launch_config(write_temp(kGood));
    EXPECT_EQ(c.domain_id, 7);
    EXPECT_EQ(c.ns, "/robot");
    EXPECT_TRUE(c.dds.custom);
    EXPECT_FALSE(c.dds.multicast);
    EXPECT_EQ(c.qos.at(TopicRole::kStream).depth, 3);
    EXPECT_TRUE(c.qos.at(TopicRole::kStream).keep_all);
    EXPECT_EQ(c.topic_roles.at("points"), TopicRole::kStream);
    EXPECT_EQ(c.on_error, ErrorPolicy::kRestart);
    ASSERT_EQ(c.components.size(), 2u);
    EXPECT_EQ(c.components[0].name, "player");
    EXPECT_EQ(c.components[0].remaps.at("points"), "/kitti/points");
    EXPECT_EQ(c.components[0].remap_lines.at("points"), 19);
    EXPECT_EQ(c.components[1].name, "trajectory_writer");  // defaults to its type
    EXPECT_EQ(c.components[0].params["rate"].as<double>(), 1.0);
}

TEST(LaunchConfig, OverridesFromTheCommandLine) {
    const LaunchConfig c = load_launch_config(
        write_temp(kGood), {"player.rate=4", "player.new.deep=x", "domain_id=9"});
    EXPECT_EQ(c.components[0].params["rate"].as<double>(), 4.0);
    EXPECT_EQ(c.components[0].params["new"]["deep"].as<std::string>(), "x");
    EXPECT_EQ(c.domain_id, 9);
}

TEST(LaunchConfig, RemapsAndTopLevelMapsFromTheCommandLine) {
    const LaunchConfig c = load_launch_config(
        write_temp(kGood),
        {"player.remap.points=/other/points", "trajectory_writer.remap.odometry=/x",
         "dds={interfaces: [lo], multicast: false, peers: [127.0.0.2]}"});
    EXPECT_EQ(c.components[0].remaps.at("points"), "/other/points");
    EXPECT_EQ(c.components[1].remaps.at("odometry"), "/x");
    for (const auto& kv : c.components[0].params) EXPECT_NE(kv.first.as<std::string>(), "remap");
    ASSERT_EQ(c.dds.peers.size(), 1u);
    EXPECT_EQ(c.dds.peers[0], "127.0.0.2");
    try {
        load_launch_config(write_temp(kGood), {"player.remap.points=[a, b]"});
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "<command line>:0: --set player.remap.points: expected a topic name");
    }
}

TEST(LaunchConfig, BadConfigurationsNameLineAndKey) {
    EXPECT_EQ(
        error_of("domain_id: 1\ncomponentz: []\n"),
        ":2: componentz: unknown key (known: components, dds, domain_id, exit_when_sources_done, "
        "finish_timeout_s, idle_exit_s, max_restarts, namespace, on_component_error, qos, "
        "shutdown_timeout_s, "
        "topics)");
    EXPECT_EQ(error_of("domain_id: x\ncomponents: [{type: a}]\n"),
              ":1: domain_id: expected an integer");
    EXPECT_EQ(error_of("components: []\n"),
              ":1: components: expected a non-empty list of components");
    EXPECT_EQ(error_of("components:\n  - {type: a, name: x}\n  - {type: b, name: x}\n"),
              ":3: x: two components with this name");
    EXPECT_EQ(error_of("topics: {points: fast}\ncomponents: [{type: a}]\n"),
              ":1: topics.points: expected a role: sensor, state, map or stream");
    EXPECT_EQ(error_of("on_component_error: retry\ncomponents: [{type: a}]\n"),
              ":1: on_component_error: expected 'stop' or 'restart', got 'retry'");
    EXPECT_EQ(error_of("qos: {sensor: {depht: 3}}\ncomponents: [{type: a}]\n").substr(0, 26),
              ":1: qos.sensor.depht: unkn");
    EXPECT_EQ(error_of("components:\n  - type: a\n    parms: {}\n"),
              ":3: components[].parms: unknown key (known: name, params, remap, type)");
    EXPECT_EQ(error_of("components: [{type: a}]\nbad: [\n"),
              ":3: yaml: end of sequence flow not found");
}

TEST(LaunchConfig, MissingFileAndBadOverride) {
    try {
        load_launch_config("/no/such/launch.yaml");
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()), "/no/such/launch.yaml:0: launch config: no such file");
    }
    const std::string path = write_temp(kGood);
    try {
        load_launch_config(path, {"nobody.rate=1"});
        FAIL();
    } catch (const ConfigError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "<command line>:0: --set nobody.rate: no component named 'nobody' in the launch "
                  "config");
    }
}

TEST(LaunchConfig, CycloneXmlForLoopbackUnicast) {
    DdsSettings d;
    d.custom = true;
    d.interfaces = {"lo"};
    d.peers = {"127.0.0.1"};
    d.multicast = false;
    const std::string xml = cyclone_xml(d);
    EXPECT_NE(xml.find("<NetworkInterface name=\"lo\"/>"), std::string::npos);
    EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos);
    EXPECT_NE(xml.find("<Peer Address=\"127.0.0.1\"/>"), std::string::npos);
    EXPECT_NE(xml.find("<ParticipantIndex>auto</ParticipantIndex>"), std::string::npos);
}
