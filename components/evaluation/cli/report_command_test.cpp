// ltm_eval report on a small run folder with known contents: every section it should find.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/core/cdr_cursor.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/trajectory_io.hpp"
#include "recorder/core/mcap_writer.hpp"

namespace ltm::eval {
namespace {

namespace fs = std::filesystem;

int run_eval(const std::string& args, std::string* output) {
    static int calls = 0;  // one file per process and call: ctest runs tests in parallel processes
    const std::string log = testing::TempDir() + "ltm_eval_report_output_" +
                            std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".txt";
    const int status = std::system(
        (std::string(LTM_BINARY_DIR) + "/bin/ltm_eval " + args + " > " + log + " 2>&1").c_str());
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    *output = ss.str();
    return WEXITSTATUS(status);
}

std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::vector<std::uint8_t> status_cdr(double stamp, std::uint8_t state, const std::string& message) {
    std::vector<std::uint8_t> out = {0, 1, 0, 0};
    common::CdrWriter w(out);
    w.write(static_cast<std::int32_t>(stamp));
    w.write(static_cast<std::uint32_t>((stamp - static_cast<std::int32_t>(stamp)) * 1e9));
    w.write(static_cast<std::uint32_t>(4));
    w.bytes("map", 4);
    w.write(state);
    w.write(static_cast<std::uint8_t>(state == 1 || state == 3));
    w.write(0.8f);
    w.write(0.9f);
    w.write(0.0);
    w.write(0.0);
    w.write(static_cast<std::uint8_t>(state == 3));
    w.write(0.12);
    w.write(static_cast<std::uint32_t>(1));
    w.write(static_cast<std::uint32_t>(0));
    w.write(static_cast<std::uint32_t>(message.size() + 1));
    w.bytes(message.c_str(), message.size() + 1);
    return out;
}

// A run: 100 scans along a square's side, the localisation 5 cm to the side, a map cloud, its
// status recorded (lost at scan 40, re-localised at 45), the launcher's run.txt and a host.log.
fs::path make_run(const std::string& name) {
    const fs::path dir = fs::path(testing::TempDir()) / ("ltm_eval_report_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir / "maintenance");
    common::Trajectory truth, estimate;
    for (int i = 0; i < 100; ++i) {
        common::StampedPose p;
        p.stamp = 10.0 + 0.1 * i;
        p.pose.translation() = Eigen::Vector3d(0.5 * i, 0.0, 0.0);
        truth.push_back(p);
        p.pose.translation().y() += (i % 2 ? 0.05 : -0.05);
        estimate.push_back(p);
    }
    common::write_tum_trajectory((dir / "ground_truth_tum.txt").string(), truth);
    common::write_tum_trajectory((dir / "localisation_tum.txt").string(), estimate);
    common::PlyCloud map;
    for (int i = 0; i < 500; ++i) map.points.emplace_back(0.1f * i, 3.0f, 0.0f);
    common::write_ply((dir / "global_map.ply").string(), map);
    {
        recorder::McapWriter mcap((dir / "run.mcap").string());
        const auto schema =
            mcap.add_schema("ltm_msgs::msg::dds_::LocalisationStatus_", "omgidl", "");
        const auto channel = mcap.add_channel(schema, "rt/robot/localisation_status");
        for (int i = 0; i < 100; ++i) {
            const std::uint8_t state = i < 40 ? 1 : i < 45 ? 2 : i == 45 ? 3 : 1;
            const auto cdr =
                status_cdr(10.0 + 0.1 * i, state, i == 45 ? "relocalised: place 3" : "ok");
            const std::uint64_t t = static_cast<std::uint64_t>((10.0 + 0.1 * i) * 1e9);
            mcap.write(channel, t, t, cdr.data(), cdr.size());
        }
        mcap.close();
    }
    std::ofstream(dir / "run.txt")
        << "command: ./ltm run robot_lifelong.yaml\nlaunch: /x/robot_lifelong.yaml\n";
    std::ofstream(dir / "launch.yaml") << "components: []\n";
    std::ofstream(dir / "host.log")
        << "ltm: running /x/robot_lifelong.yaml (results: here)\n"
        << "12:00:00.000 info  [host] running 9 components on DDS domain 7\n"
        << "12:00:01.000 warn  [odometry] scan 3: <odd>\n";
    std::ofstream(dir / "exit_status") << "0\n";
    std::ofstream(dir / "maintenance" / "changes.txt")
        << "session 0 pass 0 at 5.0 s: 3 moving, 2 vanished, 1 new segments; 40 of 900 voxels "
           "removed, 800 judged\n";
    return dir;
}

TEST(ReportCommand, WritesEverySectionOfARun) {
    const fs::path dir = make_run("sections");
    std::string out;
    ASSERT_EQ(run_eval("report " + dir.string(), &out), 0) << out;
    EXPECT_NE(out.find("report.html"), std::string::npos) << out;
    const std::string html = read(dir / "report.html");
    for (const char* expected :
         {"robot_lifelong.yaml", "running 9 components", "warnings / errors in host.log",
          "&lt;odd&gt;", "ATE rmse", "<td>localisation</td><td>100</td>", "data:image/png;base64,",
          "global_map.ply (500 points", "<td>tracking</td><td>94</td>", "<td>lost</td><td>5</td>",
          "relocalised: place 3", "3 moving, 2 vanished, 1 new segments; 40 voxels removed",
          "<a href=\"global_map.ply\">", "the launch config (launch.yaml)"}) {
        EXPECT_NE(html.find(expected), std::string::npos) << expected;
    }
    // ATE of a +-5 cm zig-zag: 0.050 m.
    EXPECT_NE(html.find("<td>0.050</td>"), std::string::npos);
}

// The report in a real browser (Debian's chromium, headless): every picture shown, no console
// error, and a screenshot of the page.
TEST(ReportCommand, RendersInHeadlessChromium) {
    if (std::system("command -v chromium > /dev/null 2>&1") != 0) {
        GTEST_SKIP() << "chromium is not installed (apt-get install chromium): the report's "
                        "render test is skipped";
    }
    const fs::path dir = make_run("chromium");
    std::string out;
    ASSERT_EQ(run_eval("report " + dir.string(), &out), 0) << out;
    const fs::path profile = dir / "chromium-profile";
    const std::string browser =
        "timeout 120 chromium --headless=new --no-sandbox --disable-gpu "
        "--hide-scrollbars --no-first-run --user-data-dir=" +
        profile.string() + " --virtual-time-budget=5000 ";
    const fs::path dom = dir / "dom.html", console = dir / "console.txt", shot = dir / "report.png";
    ASSERT_EQ(std::system((browser + "--enable-logging=stderr --v=0 --dump-dom file://" +
                           (dir / "report.html").string() + " > " + dom.string() + " 2> " +
                           console.string())
                              .c_str()),
              0)
        << read(console);
    const std::string page = read(dom);
    EXPECT_NE(page.find("data-pictures-broken=\"0\""), std::string::npos) << read(console);
    const std::size_t at = page.find("data-pictures=\"");
    ASSERT_NE(at, std::string::npos) << "the page's script did not run";
    EXPECT_GE(std::stoi(page.substr(at + 15)), 4);  // trajectory, errors, map, timeline
    // Console messages of the page itself (chromium's own dbus/GPU noise is not the page's).
    std::istringstream lines(read(console));
    for (std::string line; std::getline(lines, line);) {
        EXPECT_EQ(line.find("CONSOLE"), std::string::npos) << line;
        EXPECT_EQ(line.find("Uncaught"), std::string::npos) << line;
    }
    ASSERT_EQ(std::system((browser + "--window-size=1000,1400 --screenshot=" + shot.string() +
                           " file://" + (dir / "report.html").string() + " > /dev/null 2>&1")
                              .c_str()),
              0);
    const std::string png = read(shot);
    ASSERT_GT(png.size(), 20000u) << "a blank page compresses to a few kB";
    EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(ReportCommand, AnEmptyFolderStillGetsAReportAndAMissingOneIsRefused) {
    const fs::path dir = fs::path(testing::TempDir()) / "ltm_eval_report_empty";
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::string out;
    ASSERT_EQ(run_eval("report " + dir.string(), &out), 0) << out;
    const std::string html = read(dir / "report.html");
    EXPECT_NE(html.find("No trajectory"), std::string::npos);
    EXPECT_NE(html.find("No host.log"), std::string::npos);
    EXPECT_EQ(run_eval("report " + (dir / "nothing").string(), &out), 2) << out;
    EXPECT_NE(out.find("no such run folder"), std::string::npos) << out;
    std::ofstream(dir / "localisation_tum.txt") << "not a pose\n";
    ASSERT_EQ(run_eval("report " + dir.string(), &out), 0) << out;
    EXPECT_NE(read(dir / "report.html").find("unreadable"), std::string::npos);
}

}  // namespace
}  // namespace ltm::eval
