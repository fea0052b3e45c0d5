// The base station's downlink journal pruned (issue 28, item 4) and a base station's map_to_odom
// used by a split robot only with the version it belongs to (issue 26), through the host:
// launch_configs/robot.yaml (the simulator as its sensor, slowed down) and
// base_station_multi.yaml as two processes on their own domain, over tiny_week.
// Monday: while the robot drives, a version is committed on request (`./ltm map commit`); the
// downlink forgets what it holds; the base station is killed (SIGKILL) and started again: it
// starts from that version, does not replay what the version holds, the robot resends the rest,
// and the day's version has every keyframe once.
// Tuesday: the base station continues v0002 but offers nothing (no site_publisher), the robot has
// no version: the base station's map_to_odom is v0002's frame, which this robot does not have, so
// the robot publishes no pose (it did before: the odometry under that map_to_odom).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

#include "common/core/file_io.hpp"
#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "map/core/link_applied.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_store.hpp"

namespace fs = std::filesystem;
using ltm::tests::kConfigs;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kScenario = ltm::tests::scenario("tiny_week.yaml");
const std::string kDds = "dds={interfaces: [lo], multicast: false, peers: [127.0.0.1]}";

// Bytes of the segment files under a journal folder (every run).
std::uint64_t journal_bytes(const std::string& dir) {
    std::uint64_t n = 0;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file() && it->path().extension() == ".ltmj") n += it->file_size();
    return n;
}

std::size_t lines(const std::string& file) {
    std::ifstream in(file);
    std::size_t n = 0;
    for (std::string l; std::getline(in, l);) n += !l.empty() && l[0] != '#';
    return n;
}

class BaseJournal : public ltm::tests::TempDirTest {
  protected:
    BaseJournal() : TempDirTest("ltm_base_journal_") {}

    // Each test on a domain of its own (ctest runs the two at once: on one domain the second
    // test's robot heard the first test's base station).
    std::string domain_ = "domain_id=177";

    // robot.yaml with the simulator as its sensor at `rate` and the poses written.
    std::string robot_config(double rate) {
        std::string text = common::read_file(kConfigs + "robot.yaml", "robot.yaml");
        const std::size_t from = text.find("  - name: player\n");
        const std::size_t to = text.find("  - name: odometry\n");
        EXPECT_TRUE(from != std::string::npos && to != std::string::npos && from < to);
        text.replace(from, to - from,
                     "  - name: player\n    type: simulator\n    params: {scenario: " + kScenario +
                         ", mode: realtime, rate: " + std::to_string(rate) +
                         ", wait_for_readers: 3}\n");
        text += R"(  - name: localised
    type: trajectory_writer
    params:
      tum_file: ${LTM_OUT}/localisation_tum.txt
      input: pose_with_covariance
)";
        return write("robot.yaml", text);
    }

    // base_station_multi.yaml without its site publishers: the robot is offered nothing.
    std::string base_without_offers() {
        std::string text = common::read_file(kConfigs + "base_station_multi.yaml", "base");
        for (const std::string name : {"site_publisher_robot1", "site_publisher_robot2"}) {
            const std::size_t from = text.find("  - name: " + name);
            const std::size_t to = text.find("\n  - name: ", from + 1);
            EXPECT_NE(from, std::string::npos);
            EXPECT_NE(to, std::string::npos);
            text.erase(from, to + 1 - from);
        }
        return write("base_no_offers.yaml", text);
    }

    // The hosts' command lines (LTM_SITE and LTM_OUT set for them; a Process is not moved: its
    // destructor kills the child).
    std::vector<std::string> base(const std::string& config, const std::string& out) {
        setenv("LTM_SITE", path("base_site").c_str(), 1);
        setenv("LTM_OUT", path(out).c_str(), 1);
        return {kHost,   config,         "--set", domain_,
                "--set", kDds,           "--set", "mapping.preset=vlp16",
                "--set", "idle_exit_s=6"};
    }
    std::vector<std::string> robot(int session, double rate, const std::string& site) {
        const std::string n = std::to_string(session);
        setenv("LTM_SITE", path(site).c_str(), 1);
        setenv("LTM_OUT", path("robot" + n).c_str(), 1);
        return {kHost,   robot_config(rate),
                "--set", domain_,
                "--set", kDds,
                "--set", "namespace=/robot1",
                "--set", "odometry.preset=vlp16",
                "--set", "keyframe_digest.preset=vlp16",
                "--set", "localisation.preset=vlp16",
                "--set", "player.session=" + n};
    }
};

}  // namespace

TEST_F(BaseJournal, ACommittedVersionPrunesTheJournalAndARestartedBaseStationResumesAfterIt) {
    const std::string journal = path("base0/downlink/robot1");
    auto first = std::make_unique<Process>(base(kConfigs + "base_station_multi.yaml", "base0"),
                                           path("base0_host"));
    // Monday at a fifth of the sensor's rate: about 20 s of driving.
    Process drive(robot(0, 0.2, "robot_site"), path("robot0_host"));
    // Once some keyframes are in, a version on request.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (journal_bytes(journal) < 200 * 1024 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
    ASSERT_GE(journal_bytes(journal), 200u * 1024) << first->err();
    Process request(
        {kHost, kConfigs + "tools/map_request.yaml", "--set", "map_request.command=commit", "--set",
         domain_, "--set", "namespace=\"\"", "--set", kDds},
        path("request"));
    ASSERT_EQ(request.wait(90), 0) << request.err() << first->err();
    ASSERT_NE(request.err().find("committed v0001"), std::string::npos) << request.err();
    // The downlink sees the version and forgets what it holds.
    ASSERT_TRUE(first->wait_for_log("KiB of journal released", 30)) << first->err();
    const std::uint64_t kept = journal_bytes(journal);
    const map::LinkApplied v1 = map::read_link_applied(path("base_site/versions/v0001/map"));
    ASSERT_EQ(v1.count("robot1"), 1u) << "v0001 records what it holds of robot1's packets";
    const std::uint64_t held = v1.at("robot1").begin()->second;
    EXPECT_GT(held, 0u);

    // A crash of the base station while the robot drives on, and a restart on the same folders.
    first->signal(SIGKILL);
    EXPECT_EQ(first->wait(30), 128 + SIGKILL);
    first.reset();
    Process second(base(kConfigs + "base_station_multi.yaml", "base0"), path("base0b_host"));
    ASSERT_EQ(drive.wait(400), 0) << drive.err();
    ASSERT_EQ(second.wait(400), 0) << second.err();
    const std::string log = second.err();
    EXPECT_NE(log.find("continuing v0001"), std::string::npos) << log;
    EXPECT_NE(log.find("packets through " + std::to_string(held) +
                       " are in site version v0001 (the mapping starts from it): not replayed"),
              std::string::npos)
        << log;
    EXPECT_EQ(log.find("not added"), std::string::npos) << "nothing applied twice\n" << log;

    // The day's version: every keyframe the robot sent, once.
    const auto versions = map::SiteStore(path("base_site")).versions();
    ASSERT_EQ(versions.size(), 2u) << log;
    for (const auto& v : versions) EXPECT_TRUE(v.intact) << v.name << ": " << v.problem;
    const map::LoadedMap day = map::load_map(versions[1].map_dir());
    // A packet applied twice would be a keyframe of the same scan (stamp) twice, in the
    // restarted base station's session beside v0001's.
    std::set<long long> stamps;
    for (const auto& k : day.map.keyframes)
        EXPECT_TRUE(stamps.insert(std::llround(k->data.stamp * 1e3)).second)
            << "keyframe " << k->data.id << " (stamp " << k->data.stamp << ") twice";
    const map::LinkApplied v2 = map::read_link_applied(versions[1].map_dir());
    ASSERT_EQ(v2.count("robot1"), 1u);
    EXPECT_GT(v2.at("robot1").begin()->second, held) << "the rest is in v0002";
    // Every keyframe the robot made, once.
    const std::string made = drive.err();
    const std::size_t at = made.find(" keyframes digested");
    ASSERT_NE(at, std::string::npos) << made;
    const std::size_t from = made.rfind(' ', at - 1) + 1;
    EXPECT_EQ(day.map.keyframes.size(), std::stoul(made.substr(from, at - from))) << log;
    std::printf(
        "base journal: v0001 held packets through %llu, v0002 through %llu; %zu keyframes; "
        "journal %llu KiB after v0001, %llu KiB at the end (before the next start)\n",
        static_cast<unsigned long long>(held),
        static_cast<unsigned long long>(v2.at("robot1").begin()->second), day.map.keyframes.size(),
        static_cast<unsigned long long>(kept >> 10),
        static_cast<unsigned long long>(journal_bytes(journal) >> 10));
    // A new site on both sides on Monday: the robot's poses are the odometry under the base
    // station's map_to_odom.
    EXPECT_GT(lines(path("robot0/localisation_tum.txt")), 0u);
}

TEST_F(BaseJournal, ARobotWithoutTheBaseStationsVersionDoesNotPoseInItsFrame) {
    domain_ = "domain_id=178";
    // v0001 on the base station only (a day's map, made through the host).
    {
        Process b(base(kConfigs + "base_station_multi.yaml", "base0"), path("base0_host"));
        Process r(robot(0, 1.0, "robot_site0"), path("robot0_host"));
        ASSERT_EQ(r.wait(400), 0) << r.err();
        ASSERT_EQ(b.wait(400), 0) << b.err();
    }
    ASSERT_EQ(map::SiteStore(path("base_site")).versions().size(), 1u);
    // Tuesday: the base station continues v0001 and offers it to nobody; the robot has no version.
    Process b(base(base_without_offers(), "base1"), path("base1_host"));
    Process r(robot(1, 1.0, "robot_site1"), path("robot1_host"));
    ASSERT_EQ(r.wait(400), 0) << r.err();
    ASSERT_EQ(b.wait(400), 0) << b.err();
    EXPECT_NE(r.err().find("the base station's map_to_odom belongs to site version v0001, which "
                           "this robot does not have yet"),
              std::string::npos)
        << r.err();
    EXPECT_EQ(lines(path("robot1/localisation_tum.txt")), 0u)
        << "no pose in a frame the robot has no map of";
}
