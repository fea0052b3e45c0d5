// The host end to end, as a separate process: composition, bad configurations, signals, failure
// policies, two processes over DDS.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>

#include "common/core/kitti_io.hpp"
#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::kTestHost;
using ltm::tests::Process;

namespace {

const std::string kFixture = std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini";

// Loopback only, unicast discovery, a domain of the test's own: tests may run in parallel.
std::string dds_section(int domain) {
    return "domain_id: " + std::to_string(domain) + "\ndds: " + ltm::tests::kLoopbackDds + "\n";
}

class HostTest : public ltm::tests::TempDirTest {
  protected:
    HostTest() : TempDirTest("ltm_host_e2e_") {}
    std::size_t count_files(const std::string& sub, const std::string& ext) const {
        std::size_t n = 0;
        if (!fs::is_directory(dir_ / sub)) return 0;
        for (const auto& e : fs::directory_iterator(dir_ / sub))
            if (e.path().extension() == ext) ++n;
        return n;
    }
};

std::size_t ply_vertices(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    while (std::getline(in, line) && line != "end_header")
        if (line.rfind("element vertex ", 0) == 0) return std::stoul(line.substr(15));
    return 0;
}

std::size_t lines(const std::string& text) {
    std::size_t n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

}  // namespace

TEST_F(HostTest, SourceToWriterWritesExactlyNFrames) {
    for (const std::string mode : {"fast", "realtime"}) {
        const std::string out = "clouds_" + mode;
        const std::string launch = write("compose_" + mode + ".yaml", dds_section(151) + R"(
topics: {points: stream}
components:
  - name: player
    type: kitti_player
    params: {path: )" + kFixture + ", mode: " + mode + R"(, rate: 5.0}
  - name: writer
    type: cloud_writer
    params: {dir: )" + path(out) + R"(}
)");
        Process host({kHost, launch}, path("host_" + mode));
        ASSERT_EQ(host.wait(60), 0) << host.err();
        const auto scans = ltm::common::list_kitti_scans(kFixture);
        ASSERT_EQ(count_files(out, ".ply"), scans.size()) << host.err();
        for (std::size_t i = 0; i < scans.size(); ++i) {
            char name[32];
            std::snprintf(name, sizeof name, "/%06zu.ply", i);
            EXPECT_EQ(ply_vertices(path(out) + name), ltm::common::read_kitti_bin(scans[i]).size());
        }
    }
}

TEST_F(HostTest, CloudFolderPlayerWithPosesFeedsTheTrajectoryWriter) {
    // A folder of PLY scans with a KITTI poses file, as exported by many mapping tools.
    fs::create_directories(dir_ / "scans");
    std::string poses;
    for (int i = 0; i < 4; ++i) {
        std::ofstream ply(path("scans/" + std::to_string(100 + i) + ".ply"));
        ply << "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float "
               "y\nproperty float z\n"
               "property float intensity\nend_header\n"
            << i << " 0 0 1\n0 " << i << " 0 2\n";
        poses += "1 0 0 " + std::to_string(i) + " 0 1 0 0 0 0 1 0\n";
    }
    std::ofstream(path("poses.txt")) << poses;
    const std::string launch = write("folder.yaml", dds_section(160) + R"(
topics: {points: stream, ground_truth: stream}
components:
  - name: player
    type: cloud_folder_player
    params: {path: )" + path("scans") +
                                                        ", poses_file: " + path("poses.txt") +
                                                        R"(, mode: fast, period_s: 0.5}
  - name: traj
    type: trajectory_writer
    params: {kitti_file: )" + path("traj.txt") + ", tum_file: " +
                                                        path("traj_tum.txt") + R"(, input: pose}
    remap: {pose: ground_truth}
  - name: writer
    type: cloud_writer
    params: {dir: )" + path("clouds") + R"(, format: bin}
)");
    Process host({kHost, launch}, path("host"));
    ASSERT_EQ(host.wait(60), 0) << host.err();
    EXPECT_EQ(count_files("clouds", ".bin"), 4u);
    EXPECT_EQ(ltm::common::read_kitti_bin(path("clouds/000003.bin")).points[0].x(), 3.0f);
    std::ifstream tum(path("traj_tum.txt"));
    std::vector<std::string> rows;
    for (std::string l; std::getline(tum, l);) rows.push_back(l);
    ASSERT_EQ(rows.size(), 4u);
    EXPECT_EQ(rows[3].substr(0, 24), "1.500000000 3.000000000 ");
}

TEST_F(HostTest, SimulatorStreamsLiveThroughTheHost) {
    const std::string scenario = ltm::tests::scenario("tiny_loop.yaml");
    const std::string launch = write("sim.yaml", dds_section(161) + R"(
topics: {points: stream, ground_truth: stream}
components:
  - name: sim
    type: simulator
    params: {scenario: )" + scenario + R"(, mode: fast, count: 8}
  - name: writer
    type: cloud_writer
    params: {dir: )" + path("clouds") + R"(, format: bin}
  - name: traj
    type: trajectory_writer
    params: {kitti_file: )" + path("truth.txt") + R"(, input: pose}
    remap: {pose: ground_truth}
)");
    Process host({kHost, launch}, path("host"));
    ASSERT_EQ(host.wait(120), 0) << host.err();
    ASSERT_EQ(count_files("clouds", ".bin"), 8u);
    EXPECT_GT(ltm::common::read_kitti_bin(path("clouds/000007.bin")).size(), 1000u);
    std::ifstream truth(path("truth.txt"));
    std::size_t n = 0;
    for (std::string l; std::getline(truth, l);) ++n;
    EXPECT_EQ(n, 8u);
}

TEST_F(HostTest, EveryShippedLaunchConfigIsValid) {
    setenv("LTM_DATA", kFixture.c_str(), 1);
    setenv("LTM_OUT", path("out").c_str(), 1);
    setenv("LTM_SCENARIO", (ltm::tests::scenario("tiny_loop.yaml")).c_str(), 1);
    std::size_t checked = 0;
    for (const auto& e : fs::directory_iterator(std::string(LTM_SOURCE_DIR) + "/launch_configs")) {
        if (e.path().extension() != ".yaml") continue;
        Process host({kHost, e.path().string(), "--check"},
                     path("check_" + e.path().stem().string()));
        EXPECT_EQ(host.wait(120), 0) << e.path() << ": " << host.err();
        ++checked;
    }
    EXPECT_GE(checked, 5u);
}

struct BadCase {
    const char* name;
    const char* components;  // YAML of the components list
    const char* expected;    // regex on the single stderr line
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadConfigTest : public HostTest, public ::testing::WithParamInterface<BadCase> {};

TEST_P(BadConfigTest, ExitsNonZeroWithOneLineNamingFileLineAndKey) {
    const BadCase& c = GetParam();
    const std::string launch = write("bad.yaml", dds_section(152) + "components:\n" + c.components);
    Process host({kHost, launch}, path("host"));
    EXPECT_EQ(host.wait(30), 2);
    const std::string err = host.err();
    EXPECT_EQ(lines(err), 1u) << err;
    EXPECT_TRUE(
        std::regex_search(err, std::regex(std::string("^ltm_host: ") + launch + c.expected)))
        << err;
    EXPECT_FALSE(fs::exists(path("never")));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadConfigTest,
    ::testing::Values(
        BadCase{"UnknownType", "  - name: x\n    type: kitti_playr\n",
                ":5: x\\.type: unknown component type 'kitti_playr' \\(known: .*kitti_player.*\\)"},
        BadCase{"UnknownParameter",
                "  - name: w\n    type: cloud_writer\n    params: {dir: /tmp/never, evry: 2}\n",
                ":6: w\\.evry: unknown parameter \\(known: dir, every, format, inputs\\)"},
        BadCase{"IllTypedParameter",
                "  - name: w\n    type: cloud_writer\n    params:\n      dir: /tmp/never\n      "
                "every: often\n",
                ":8: w\\.every: expected an integer, got 'often'"},
        BadCase{"RemapOfUnknownTopic",
                "  - name: w\n    type: cloud_writer\n    params: {dir: /tmp/never}\n    remap: "
                "{pointz: /a}\n",
                ":7: w\\.remap\\.pointz: component type 'cloud_writer' has no topic 'pointz' "
                "\\(its topics: "
                "/points, /local_map, /mesh\\)"},
        BadCase{"MissingFolder",
                "  - name: p\n    type: kitti_player\n    params: {path: /no/such/folder}\n",
                ":6: p\\.path: no such folder: /no/such/folder"},
        BadCase{"BadValue",
                "  - name: p\n    type: kitti_player\n    params: {path: /tmp, mode: turbo}\n",
                ":6: p\\.mode: expected 'realtime' or 'fast', got 'turbo'"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST_F(HostTest, MissingLaunchFileIsOneLine) {
    Process host({kHost, path("nothing.yaml")}, path("host"));
    EXPECT_EQ(host.wait(30), 2);
    EXPECT_EQ(host.err(),
              "ltm_host: " + path("nothing.yaml") + ":0: launch config: no such file\n");
}

TEST_F(HostTest, CycloneMessagesComeThroughTheHostsLogger) {
    // A bad element in the user's Cyclone configuration: Cyclone's own message in ltm's log
    // format, then one line saying what failed.
    const std::string launch = write("dds.yaml", R"(domain_id: 158
components:
  - name: w
    type: trajectory_writer
    params: {tum_file: )" + path("x.txt") + "}\n");
    ::setenv("CYCLONEDDS_URI", "<Tracing><Bogus>1</Bogus></Tracing>", 1);
    Process host({kHost, launch}, path("host"));
    ::unsetenv("CYCLONEDDS_URI");
    EXPECT_EQ(host.wait(30), 2);
    EXPECT_NE(host.err().find("error [dds] Bogus: unknown element (CYCLONEDDS_URI"),
              std::string::npos)
        << host.err();
    EXPECT_NE(host.err().find("ltm_host: DDS: creating DDS domain 158"), std::string::npos)
        << host.err();
}

TEST_F(HostTest, SigtermStopsCleanlyAndFlushes) {
    const std::string launch =
        write("loop.yaml", dds_section(153) + R"(
components:
  - name: player
    type: kitti_player
    params: {path: )" + kFixture +
                               ", poses_file: " + kFixture +
                               R"(/poses_semantickitti.txt, loop: true, rate: 2.0}
  - name: traj
    type: trajectory_writer
    params: {tum_file: )" + path("gt_tum.txt") +
                               R"(, input: pose}
    remap: {pose: ground_truth}
)");
    Process host({kHost, launch}, path("host"));
    // Wait until poses flow (the writer logs nothing per pose; the player logs when it starts).
    for (int i = 0; i < 500 && host.err().find("playing 3 scans") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(800));
    const auto t0 = std::chrono::steady_clock::now();
    host.signal(SIGTERM);
    const int rc = host.wait(60);
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(rc, 0) << host.err();
    EXPECT_LT(took, 30.0) << "shutdown took " << took << " s";  // the default stop deadline
    EXPECT_NE(host.err().find("received SIGTERM"), std::string::npos);
    EXPECT_NE(host.err().find("saved trajectory (traj): " + path("gt_tum.txt")), std::string::npos)
        << host.err();
    EXPECT_NE(host.err().find("stopped cleanly"), std::string::npos);
    std::ifstream tum(path("gt_tum.txt"));
    std::string first;
    ASSERT_TRUE(std::getline(tum, first)) << "no pose flushed";
    EXPECT_EQ(std::count(first.begin(), first.end(), ' '), 7);
}

TEST_F(HostTest, ThrowingComponentIsNamedAndStopsTheHost) {
    const std::string launch = write("fault.yaml", dds_section(154) + R"(
topics: {points: stream}
components:
  - name: player
    type: kitti_player
    params: {path: )" + kFixture + R"(, mode: fast}
  - name: faulty
    type: test_faulty
    params: {throw_at: 2}
  - name: writer
    type: cloud_writer
    params: {dir: )" + path("clouds") + R"(}
)");
    Process host({kTestHost, launch}, path("host"));
    EXPECT_EQ(host.wait(60), 1);
    const std::string err = host.err();
    EXPECT_NE(
        err.find(
            "component 'faulty' (test_faulty) threw in its handler of /points: injected fault"),
        std::string::npos)
        << err;
    EXPECT_NE(err.find("stopping (on_component_error: stop)"), std::string::npos) << err;
    EXPECT_NE(err.find("[writer] wrote"), std::string::npos)
        << "the other components were not shut down: " << err;
}

TEST_F(HostTest, RestartPolicyRestartsThenGivesUp) {
    const std::string launch = write("restart.yaml", dds_section(155) + R"(
on_component_error: restart
max_restarts: 1
components:
  - name: faulty
    type: test_faulty
    params: {throw_in_activate: true}
)");
    Process host({kTestHost, launch}, path("host"));
    EXPECT_EQ(host.wait(60), 1);
    const std::string err = host.err();
    EXPECT_NE(err.find("threw in on_activate: injected fault in activate"), std::string::npos)
        << err;
    EXPECT_NE(err.find("restarting component 'faulty' (1 of 1)"), std::string::npos) << err;
    EXPECT_NE(err.find("component 'faulty' failed too often; stopping"), std::string::npos) << err;
}

TEST_F(HostTest, StuckComponentDoesNotHangTheHost) {
    const std::string launch = write("stuck.yaml", dds_section(156) + R"(
shutdown_timeout_s: 2
components:
  - name: stuck
    type: test_stuck
    params: {seconds: 60}
)");
    Process host({kTestHost, launch}, path("host"));
    for (int i = 0; i < 500 && host.err().find("running 1 components") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto t0 = std::chrono::steady_clock::now();
    host.signal(SIGINT);
    EXPECT_EQ(host.wait(20), 3);
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(took, 2.0 + 15.0);  // the deadline, and room for a loaded machine
    EXPECT_NE(host.err().find("component 'stuck' did not stop within the 2.0 s deadline (still "
                              "in on_shutdown"),
              std::string::npos)
        << host.err();
}

// A stop waits for final saves that take longer than a moment (within the deadline) and says
// what it waits for; every output is listed.
TEST_F(HostTest, StopWaitsForFinalSavesAndListsThem) {
    const std::string launch = write("saver.yaml", dds_section(162) + R"(
components:
  - name: saver
    type: test_slow_saver
    params: {seconds: 6, file: )" + path("out.txt") + R"(}
)");
    Process host({kTestHost, launch}, path("host"));
    for (int i = 0; i < 1000 && host.err().find("running 1 components") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    host.signal(SIGTERM);
    EXPECT_EQ(host.wait(60), 0) << host.err();
    const std::string err = host.err();
    EXPECT_NE(err.find("stopping: waiting for 'saver' (on_shutdown)"), std::string::npos) << err;
    EXPECT_NE(err.find("saved test file (saver): " + path("out.txt") + " (1 line)"),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("stopped cleanly"), std::string::npos) << err;
    EXPECT_TRUE(fs::exists(path("out.txt")));
}

// An output that could not be saved: exit 4, and the log names it.
TEST_F(HostTest, OutputNotSavedExitsFourNamingIt) {
    const std::string file = path("no_such_folder") + "/out.txt";
    const std::string launch = write("unsaved.yaml", dds_section(163) + R"(
components:
  - name: saver
    type: test_slow_saver
    params: {file: )" + file + R"(}
)");
    Process host({kTestHost, launch}, path("host"));
    for (int i = 0; i < 1000 && host.err().find("running 1 components") == std::string::npos; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    host.signal(SIGINT);
    EXPECT_EQ(host.wait(60), 4) << host.err();
    const std::string err = host.err();
    EXPECT_NE(err.find("NOT saved: test file (saver): " + file + " (cannot write)"),
              std::string::npos)
        << err;
    EXPECT_EQ(err.find("stopped cleanly"), std::string::npos) << err;
}

// As a systemd `Type=notify` unit with a watchdog (launch_configs/systemd/): READY=1 once
// running, WATCHDOG=1 while the components make progress, STOPPING=1 on SIGTERM, then exit 0.
TEST_F(HostTest, SystemdNotifyReadyWatchdogAndStop) {
    const std::string sock = path("notify.sock");
    const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    ASSERT_GE(fd, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    ASSERT_LT(sock.size(), sizeof addr.sun_path);
    std::memcpy(addr.sun_path, sock.c_str(), sock.size() + 1);
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    const std::string launch = write("notify.yaml", dds_section(164) + R"(
components:
  - name: saver
    type: test_slow_saver
    params: {file: )" + path("out.txt") + R"(}
)");
    ::setenv("NOTIFY_SOCKET", sock.c_str(), 1);
    ::setenv("WATCHDOG_USEC", "300000", 1);
    Process host({kTestHost, launch}, path("host"));
    ::unsetenv("NOTIFY_SOCKET");
    ::unsetenv("WATCHDOG_USEC");
    std::string got;
    auto receive_until = [&](const std::string& what) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (got.find(what) == std::string::npos && std::chrono::steady_clock::now() < deadline) {
            pollfd p{fd, POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0) continue;
            char buf[512];
            const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
            if (n > 0) got += std::string(buf, n) + "\n";
        }
        return got.find(what) != std::string::npos;
    };
    EXPECT_TRUE(receive_until("READY=1")) << got;
    EXPECT_TRUE(receive_until("WATCHDOG=1")) << got;
    host.signal(SIGTERM);
    EXPECT_TRUE(receive_until("STOPPING=1")) << got;
    EXPECT_EQ(host.wait(60), 0) << host.err();
    ::close(fd);
}

TEST_F(HostTest, UnsupportedPointCloudLayoutIsRejectedCleanly) {
    const std::string launch = write("badcloud.yaml", dds_section(157) + R"(
topics: {points: stream}
components:
  - {name: source, type: test_bad_cloud_source}
  - name: writer
    type: cloud_writer
    params: {dir: )" + path("clouds") + R"(}
)");
    Process host({kTestHost, launch}, path("host"));
    EXPECT_EQ(host.wait(60), 0) << host.err();
    EXPECT_NE(host.err().find("rejected point cloud 0: field 'x' is datatype 8, need float32 (7)"),
              std::string::npos)
        << host.err();
    EXPECT_EQ(count_files("clouds", ".ply"), 0u);
}

class TwoProcessTest : public HostTest, public ::testing::WithParamInterface<bool> {};

TEST_P(TwoProcessTest, SamplesCrossBetweenHosts) {
    const bool loopback_unicast = GetParam();
    const int domain = loopback_unicast ? 158 : 159;
    const std::string dds =
        loopback_unicast ? dds_section(domain) : "domain_id: " + std::to_string(domain) + "\n";
    const std::string robot = write("robot.yaml", dds + R"(
topics: {points: stream}
components:
  - name: player
    type: kitti_player
    params: {path: )" + kFixture + R"(, mode: fast, wait_for_readers: 1}
)");
    const std::string base = write("base.yaml", dds + R"(
topics: {points: stream}
idle_exit_s: 2
components:
  - name: writer
    type: cloud_writer
    params: {dir: )" + path("clouds") + R"(}
)");
    Process b({kHost, base}, path("base"));
    Process r({kHost, robot}, path("robot"));
    EXPECT_EQ(r.wait(60), 0) << r.err();
    EXPECT_EQ(b.wait(60), 0) << b.err();
    EXPECT_EQ(count_files("clouds", ".ply"), 3u) << r.err() << b.err();
}

INSTANTIATE_TEST_SUITE_P(Discovery, TwoProcessTest, ::testing::Values(false, true),
                         [](const auto& info) {
                             return info.param ? "LoopbackUnicastPeers" : "DefaultDiscovery";
                         });
