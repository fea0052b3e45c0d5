// Several robots changing one site on one day end in one version (issue 26), through the host:
// the tiny simulated site's two sessions driven at once by two simulators and odometries under
// /robot1 and /robot2, one mapping with `robots: [robot1, robot2]` on a site (as
// base_station_multi.yaml), and the `site` component last: at the end the site has ONE new
// version holding both robots' sessions, named in its version.txt.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/core/file_io.hpp"
#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "map/core/map_store.hpp"
#include "map/core/site_store.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kScenario = ltm::tests::scenario("tiny_loop.yaml");

class MultiRobotSite : public ltm::tests::TempDirTest {
  protected:
    MultiRobotSite() : TempDirTest("ltm_multi_robot_site_") {}

    // A simulator and an odometry for robot `r` (session `session` of the tiny site).
    static std::string robot(const std::string& r, int session) {
        const std::string topics = "{points: /" + r + "/points, odometry: /" + r +
                                   "/odometry, keyframe: /" + r + "/keyframe, local_map: /" + r +
                                   "/local_map, status: /" + r + "/status}";
        return "  - name: sensor_" + r +
               "\n    type: simulator\n    params: {scenario: " + kScenario +
               ", mode: fast, session: " + std::to_string(session) + "}\n    remap: {points: /" +
               r + "/points, ground_truth: /" + r + "/ground_truth}\n  - name: odometry_" + r +
               "\n    type: odometry\n    params: {preset: vlp16, threads: 1}\n    remap: " +
               topics + "\n";
    }
};

}  // namespace

TEST_F(MultiRobotSite, TwoRobotsOneDayOneVersion) {
    const std::string site = path("site");
    const std::string cfg = write("robots.yaml", R"(domain_id: 64
dds: {interfaces: [lo], multicast: false, peers: [127.0.0.1]}
topics: {/robot1/points: stream, /robot1/ground_truth: stream, /robot2/points: stream,
         /robot2/ground_truth: stream}
qos: {stream: {max_blocking_s: 2.0}}
components:
)" + robot("robot1", 0) + robot("robot2", 1) +
                                                     R"(  - name: mapping
    type: mapping
    params: {preset: vlp16, robots: [robot1, robot2], site_dir: )" +
                                                     site + R"(, save_period_s: 0}
  - name: site
    type: site
    params: {site_dir: )" + site + R"(}
)");
    Process host({kHost, cfg}, path("host"));
    ASSERT_EQ(host.wait(300), 0) << host.err();
    EXPECT_NE(host.err().find("saved site version (site): " + site + "/versions/v0001"),
              std::string::npos)
        << host.err();
    const auto versions = map::SiteStore(site).versions();
    ASSERT_EQ(versions.size(), 1u);  // one version for the day, both robots in it
    ASSERT_TRUE(versions[0].intact) << versions[0].problem;
    const map::MapData map = map::load_map(versions[0].map_dir()).map;
    ASSERT_EQ(map.sessions.size(), 2u) << host.err();
    const map::VersionSummary s = map::parse_version_text(
        common::read_file(versions[0].summary_file(), "version.txt"), "version.txt");
    ASSERT_EQ(s.sessions_added.size(), 2u);
    EXPECT_EQ(s.sessions_added[0].second, "robot1");
    EXPECT_EQ(s.sessions_added[1].second, "robot2");
    EXPECT_NE(map::version_line(s).find("(robot1), "), std::string::npos) << map::version_line(s);
}
