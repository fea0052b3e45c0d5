#include "runtime/launch_config.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>

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
    EXPECT_EQ(c.topics.at("points").role, TopicRole::kStream);
    EXPECT_FALSE(c.topics.at("points").depth);
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
        "finish_timeout_s, idle_exit_s, log, max_restarts, namespace, on_component_error, qos, "
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

namespace {

// Every Cyclone setting of a narrow, lossy link (launch_configs/README.md).
const char* kLink = R"(dds:
  interfaces: [lo]
  multicast: false
  peers: [127.0.0.1]
  fragment_size: 1344
  max_message_size: 1456 B
  max_retransmit_message_size: 1456
  socket_receive_buffer_size: 4 MiB
  socket_send_buffer_size: 2 MiB
  heartbeat_interval_s: 0.05
  nack_delay_s: 0.01
  retransmit_merging: adaptive
  whc_low: 64 KiB
  whc_high: 8 MiB
  whc_high_init: 1 MB
  whc_adaptive: false
  writer_linger_s: 15
components: [{type: a}]
)";

std::string read_file(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST(LaunchConfig, ParsesTheLinkSettings) {
    const DdsSettings d = load_launch_config(write_temp(kLink)).dds;
    EXPECT_EQ(d.fragment_size, 1344);
    EXPECT_EQ(d.max_message_size, 1456);
    EXPECT_EQ(d.max_retransmit_message_size, 1456);
    EXPECT_EQ(d.socket_receive_buffer_size, 4 << 20);
    EXPECT_EQ(d.socket_send_buffer_size, 2 << 20);
    EXPECT_EQ(d.heartbeat_interval_s, 0.05);
    EXPECT_EQ(d.nack_delay_s, 0.01);
    EXPECT_EQ(d.retransmit_merging, "adaptive");
    EXPECT_EQ(d.whc_low, 64 << 10);
    EXPECT_EQ(d.whc_high, 8 << 20);
    EXPECT_EQ(d.whc_high_init, 1000000);
    EXPECT_EQ(d.whc_adaptive, false);
    EXPECT_EQ(d.writer_linger_s, 15.0);
    // Not given: Cyclone's defaults (nothing emitted).
    const DdsSettings plain = load_launch_config(write_temp(kGood)).dds;
    EXPECT_FALSE(plain.fragment_size || plain.whc_high || plain.writer_linger_s);
    EXPECT_EQ(cyclone_xml(plain).find("Watermarks"), std::string::npos);
    EXPECT_EQ(cyclone_xml(plain).find("FragmentSize"), std::string::npos);
    // --set reaches them on a config with a dds: block and on one without.
    EXPECT_EQ(load_launch_config(write_temp(kGood), {"dds.writer_linger_s=3"}).dds.writer_linger_s,
              3.0);
    EXPECT_EQ(load_launch_config(write_temp("components: [{type: a}]\n"), {"dds.whc_high=2 MiB"})
                  .dds.whc_high,
              2 << 20);
}

TEST(LaunchConfig, BadLinkSettingsAreOneLine) {
    const auto err = [](const std::string& dds) {
        return error_of("dds:\n" + dds + "\ncomponents: [{type: a}]\n");
    };
    EXPECT_EQ(
        err("  fragment_size: 1.5 kb"),
        ":2: dds.fragment_size: expected a size in bytes (1344, 64 KiB, 8 MiB), got '1.5 kb'");
    EXPECT_EQ(err("  fragment_size: -4"),
              ":2: dds.fragment_size: expected a size in bytes (1344, 64 KiB, 8 MiB), got '-4'");
    EXPECT_EQ(err("  fragment_size: [1]"), ":2: dds.fragment_size: expected a string");
    EXPECT_EQ(err("  fragment_size: 70000"),
              ":2: dds.fragment_size: must be 512..65000 bytes, got 70000");
    EXPECT_EQ(err("  max_message_size: 1400\n  fragment_size: 1456"),
              ":3: dds.fragment_size: must not exceed dds.max_message_size (1400 B)");
    EXPECT_EQ(err("  socket_receive_buffer_size: 1 kB"),
              ":2: dds.socket_receive_buffer_size: must be 65536..2147483648 bytes, got 1000");
    EXPECT_EQ(err("  heartbeat_interval_s: 0.001"),
              ":2: dds.heartbeat_interval_s: must be 0.005..8 s");
    EXPECT_EQ(err("  nack_delay_s: soon"), ":2: dds.nack_delay_s: expected a number");
    EXPECT_EQ(err("  writer_linger_s: -1"), ":2: dds.writer_linger_s: must be 0..3600 s");
    EXPECT_EQ(err("  retransmit_merging: sometimes"),
              ":2: dds.retransmit_merging: expected never, adaptive or always, got 'sometimes'");
    EXPECT_EQ(err("  whc_adaptive: maybe"), ":2: dds.whc_adaptive: expected true or false");
    // Cyclone's "Invalid watermark settings", said before Cyclone sees them.
    EXPECT_EQ(err("  whc_high: 20 KiB"),
              ":2: dds.whc_high: expected whc_low <= whc_high_init <= whc_high and whc_low < "
              "whc_high (Cyclone's defaults 1 KiB, 30 KiB, 500 KiB for those not given), got "
              "1024, 30720, 20480 B");
    EXPECT_EQ(err("  whc_low: 1 MiB\n  whc_high: 1 MiB\n  whc_high_init: 1 MiB").substr(0, 29),
              ":4: dds.whc_high_init: expect");
    EXPECT_EQ(err("  fragmentsize: 1344").substr(0, 46),
              ":2: dds.fragmentsize: unknown key (known: extr");
}

TEST(LaunchConfig, CycloneTakesTheLinkSettings) {
    const DdsSettings d = load_launch_config(write_temp(kLink)).dds;
    const std::string xml = cyclone_xml(d);
    for (const char* e :
         {"<FragmentSize>1344 B</FragmentSize>", "<MaxMessageSize>1456 B</MaxMessageSize>",
          "<MaxRexmitMessageSize>1456 B</MaxRexmitMessageSize>",
          "<SocketReceiveBufferSize max=\"4194304 B\"/>",
          "<SocketSendBufferSize max=\"2097152 B\"/>",
          "<HeartbeatInterval>50000000 ns</HeartbeatInterval>",
          "<NackDelay>10000000 ns</NackDelay>", "<RetransmitMerging>adaptive</RetransmitMerging>",
          "<Watermarks><WhcLow>65536 B</WhcLow><WhcHigh>8388608 B</WhcHigh><WhcHighInit>1000000 "
          "B</WhcHighInit><WhcAdaptive>false</WhcAdaptive></Watermarks>",
          "<WriterLingerDuration>15000000000 ns</WriterLingerDuration>"})
        EXPECT_NE(xml.find(e), std::string::npos) << e;
    EXPECT_EQ(xml.find("65000B"), std::string::npos);  // lo's large datagrams: not over ours
    // Cyclone DDS itself accepts every element and takes the values: its configuration trace.
    const std::string log =
        ::testing::TempDir() + "cyclone_config_" + std::to_string(::getpid()) + ".log";
    const std::string uri = xml +
                            ",<CycloneDDS><Domain Id=\"any\"><Tracing><Verbosity>config</Verbosity>"
                            "<OutputFile>" +
                            log + "</OutputFile></Tracing></Domain></CycloneDDS>";
    const dds_entity_t domain = dds_create_domain(229, uri.c_str());
    ASSERT_GT(domain, 0) << dds_strretcode(domain);
    dds_delete(domain);
    const std::string trace = read_file(log);
    std::remove(log.c_str());
    for (const char* line :
         {"General/FragmentSize/#text: 1344 B", "General/MaxMessageSize/#text: 1456 B",
          "General/MaxRexmitMessageSize/#text: 1456 B",
          "Internal/SocketReceiveBufferSize[@max]: 4 MiB",
          "Internal/SocketSendBufferSize[@max]: 2 MiB", "Internal/HeartbeatInterval/#text: 50 ms",
          "Internal/NackDelay/#text: 10 ms", "Internal/RetransmitMerging/#text: adaptive",
          "Internal/Watermarks/WhcLow/#text: 64 KiB", "Internal/Watermarks/WhcHigh/#text: 8 MiB",
          "Internal/Watermarks/WhcHighInit/#text: 1000000 B",
          "Internal/Watermarks/WhcAdaptive/#text: false",
          "Internal/WriterLingerDuration/#text: 15 s"})
        EXPECT_NE(trace.find(line), std::string::npos) << line << " not in Cyclone's trace";
}

TEST(LaunchConfig, PerTopicQos) {
    const LaunchConfig c = load_launch_config(write_temp(R"(domain_id: 228
namespace: /robot
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
qos:
  state: {depth: 20}
topics:
  points: stream
  odometry: {role: state, reliable: false, depth: 1}
  /robot/status: {reliable: false}
  map_to_odom: {role: map, depth: 1, max_blocking_s: 2}
  link/packets: {keep_all: true, depth: 4, transient_local: true}
components: [{type: a}]
)"));
    const TopicQos& odometry = c.topics.at("odometry");
    EXPECT_EQ(odometry.role, TopicRole::kState);
    EXPECT_EQ(odometry.reliable, false);
    EXPECT_EQ(odometry.depth, 1);
    EXPECT_FALSE(odometry.keep_all || odometry.transient_local || odometry.max_blocking_s);
    // What the host's writers and readers get: the role's profile with the entry's keys.
    const Domain domain(c);
    const QosProfile o = domain.profile("/robot/odometry", TopicRole::kMap);
    EXPECT_FALSE(o.reliable);
    EXPECT_FALSE(o.transient_local);  // state's, not the declared map role's
    EXPECT_EQ(o.depth, 1);
    const QosProfile s = domain.profile("/robot/status", TopicRole::kState);  // no role: declared
    EXPECT_FALSE(s.reliable);
    EXPECT_EQ(s.depth, 20);  // qos.state's
    EXPECT_EQ(domain.role("/robot/status", TopicRole::kState), TopicRole::kState);
    const QosProfile m = domain.profile("/robot/map_to_odom", TopicRole::kState);
    EXPECT_TRUE(m.reliable && m.transient_local);
    EXPECT_EQ(m.depth, 1);
    EXPECT_EQ(m.max_blocking_s, 2.0);
    const QosProfile l = domain.profile("/robot/link/packets", TopicRole::kState);
    EXPECT_TRUE(l.reliable && l.keep_all && l.transient_local);
    EXPECT_EQ(l.depth, 4);
    EXPECT_EQ(domain.profile("/robot/points", TopicRole::kSensor).keep_all, true);  // old form
    EXPECT_EQ(domain.profile("/robot/other", TopicRole::kSensor).reliable, false);  // untouched
}

TEST(LaunchConfig, BadPerTopicQosIsOneLine) {
    const auto err = [](const std::string& topics) {
        return error_of("topics:\n" + topics + "\ncomponents: [{type: a}]\n");
    };
    EXPECT_EQ(err("  odometry: {role: fast}"),
              ":2: topics.odometry.role: expected sensor, state, map or stream, got 'fast'");
    EXPECT_EQ(err("  odometry: {reliabel: false}").substr(0, 50),
              ":2: topics.odometry.reliabel: unknown key (known: ");
    EXPECT_EQ(err("  odometry:\n    depth: 0"), ":3: topics.odometry.depth: must be at least 1");
    EXPECT_EQ(err("  odometry: {max_blocking_s: 0}"),
              ":2: topics.odometry.max_blocking_s: must be positive");
    EXPECT_EQ(err("  odometry: {reliable: sometimes}"),
              ":2: topics.odometry.reliable: expected true or false");
    EXPECT_EQ(err("  odometry: [state]"),
              ":2: topics.odometry: expected a role (sensor, state, map or stream) or a map of "
              "role and qos keys");
}
