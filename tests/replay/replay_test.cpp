// The product's "DDS recorder replay tests": a run is recorded once, then replayed through the
// composed pipeline and through the robot/base-station split; outputs must equal the live run's.
// In fast mode (reliable, back-pressure) replay is bit-identical: the same CDR bytes reach the same
// components in the same order.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::Process;

namespace {

const std::string kMcap = std::string(LTM_BINARY_DIR) + "/bin/ltm_mcap";
const std::string kFixture = std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini";

std::string dds(int domain) {
    return "domain_id: " + std::to_string(domain) + "\ndds: " + ltm::tests::kLoopbackDds +
           "\nnamespace: /robot\ntopics: {points: stream, ground_truth: stream}\n";
}

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The processing side of the pipeline (grows with every issue): scans and true poses to files.
std::string pipeline(const fs::path& out) {
    return R"(  - name: odometry
    type: odometry
    params: {preset: hdl64, min_scan_points: 50}
  - name: odometry_writer
    type: trajectory_writer
    params: {kitti_file: )" +
           (out / "odometry.txt").string() + R"(, tum_file: )" +
           (out / "odometry_tum.txt").string() + R"(}
  - name: writer
    type: cloud_writer
    params: {dir: )" +
           (out / "clouds").string() + R"(}
  - name: traj
    type: trajectory_writer
    params: {tum_file: )" +
           (out / "ground_truth_tum.txt").string() + R"(, input: pose}
    remap: {pose: ground_truth}
)";
}

class ReplayTest : public ltm::tests::TempDirTest {
  protected:
    ReplayTest() : TempDirTest("ltm_replay_") {}
    // Live run: player -> pipeline, with the recorder on the sensor and truth topics.
    void live_run(int domain) {
        const std::string cfg =
            write("live.yaml", dds(domain) + R"(components:
  - name: player
    type: kitti_player
    params: {path: )" + kFixture +
                                   ", poses_file: " + kFixture +
                                   R"(/poses_semantickitti.txt, mode: fast, wait_for_readers: 3}
  - name: recorder
    type: recorder
    params: {file: )" + (dir_ / "run.mcap").string() +
                                   R"(, topics: [points, ground_truth]}
)" + pipeline(dir_ / "live"));
        Process host({kHost, cfg}, (dir_ / "live").string());
        ASSERT_EQ(host.wait(120), 0) << host.err();
        ASSERT_TRUE(fs::exists(dir_ / "run.mcap"));
    }
    void expect_same_outputs(const std::string& run) {
        for (const auto& e : fs::recursive_directory_iterator(dir_ / "live")) {
            if (!e.is_regular_file()) continue;
            const fs::path rel = fs::relative(e.path(), dir_ / "live");
            ASSERT_TRUE(fs::exists(dir_ / run / rel)) << rel << " missing in " << run;
            EXPECT_EQ(read_file(e.path()), read_file(dir_ / run / rel))
                << rel << " differs in " << run;
        }
        std::size_t files = 0;
        for (const auto& e : fs::recursive_directory_iterator(dir_ / "live"))
            files += e.is_regular_file();
        EXPECT_EQ(files, 7u);  // 3 clouds, 1 local map, the truth and the odometry (KITTI, TUM)
    }
};

}  // namespace

TEST_F(ReplayTest, ComposedReplayEqualsTheLiveRunBitForBit) {
    live_run(181);
    const std::string cfg = write("replay.yaml", dds(182) + R"(components:
  - name: replay
    type: replayer
    params: {file: )" + (dir_ / "run.mcap").string() +
                                                     R"(, fast: true}
)" + pipeline(dir_ / "replayed"));
    Process host({kHost, cfg}, (dir_ / "replay").string());
    ASSERT_EQ(host.wait(120), 0) << host.err();
    expect_same_outputs("replayed");
}

TEST_F(ReplayTest, SplitReplayEqualsTheLiveRunBitForBit) {
    live_run(183);
    // Robot: the replayer. Base station: the pipeline, in another process.
    const std::string robot = write("robot.yaml", dds(184) + R"(components:
  - name: replay
    type: replayer
    params: {file: )" + (dir_ / "run.mcap").string() + R"(, fast: true, wait_for_readers: 3}
)");
    const std::string base =
        write("base.yaml", dds(184) + "idle_exit_s: 2\ncomponents:\n" + pipeline(dir_ / "split"));
    Process b({kHost, base}, (dir_ / "base").string());
    Process r({kHost, robot}, (dir_ / "robot").string());
    ASSERT_EQ(r.wait(120), 0) << r.err();
    ASSERT_EQ(b.wait(120), 0) << b.err();
    expect_same_outputs("split");
}

TEST_F(ReplayTest, TimedReplayReportsItsTimingError) {
    live_run(185);
    const std::string cfg = write("timed.yaml", dds(186) + R"(components:
  - name: replay
    type: replayer
    params: {file: )" + (dir_ / "run.mcap").string() +
                                                    R"(, rate: 1.0}
  - name: writer
    type: cloud_writer
    params: {dir: )" + (dir_ / "timed").string() + R"(}
)");
    Process host({kHost, cfg}, (dir_ / "timed").string());
    ASSERT_EQ(host.wait(120), 0) << host.err();
    EXPECT_NE(host.err().find("timing error against the recording x1.0"), std::string::npos)
        << host.err();
}

TEST_F(ReplayTest, CutRecordingReplaysWhatIsIntactAndRecoverCompletesIt) {
    live_run(187);
    // Cut the file in its last chunk: the summary and footer are gone.
    const auto size = fs::file_size(dir_ / "run.mcap");
    fs::copy_file(dir_ / "run.mcap", dir_ / "cut.mcap");
    fs::resize_file(dir_ / "cut.mcap", size - 200);
    const std::string cfg = write("cut.yaml", dds(188) + R"(components:
  - name: replay
    type: replayer
    params: {file: )" + (dir_ / "cut.mcap").string() +
                                                  R"(, fast: true, topics: [/robot/points]}
  - name: writer
    type: cloud_writer
    params: {dir: )" + (dir_ / "cut_out").string() +
                                                  R"(}
)");
    Process host({kHost, cfg}, (dir_ / "cut").string());
    ASSERT_EQ(host.wait(120), 0) << host.err();
    // The summary and footer are gone but the chunk is whole: said in one line, and replayed.
    EXPECT_NE(host.err().find("cut short"), std::string::npos) << host.err();
    EXPECT_NE(host.err().find("(replaying what is intact)"), std::string::npos) << host.err();
    std::size_t clouds = 0;
    for (const auto& e : fs::directory_iterator(dir_ / "cut_out"))
        clouds += e.path().extension() == ".ply";
    EXPECT_EQ(clouds, 3u);
    // recover completes the file: a reader then finds it whole and indexed.
    Process rec(
        {kMcap, "recover", (dir_ / "cut.mcap").string(), "-o", (dir_ / "recovered.mcap").string()},
        (dir_ / "recover").string());
    EXPECT_EQ(rec.wait(60), 0) << rec.err();
    Process verify({kMcap, "verify", (dir_ / "recovered.mcap").string()},
                   (dir_ / "verify").string());
    EXPECT_EQ(verify.wait(60), 0) << verify.err() << verify.out();
}

TEST_F(ReplayTest, UnknownTopicListsTheTopicsThatExist) {
    live_run(189);
    const std::string cfg = write("bad.yaml", dds(190) + R"(components:
  - name: replay
    type: replayer
    params: {file: )" + (dir_ / "run.mcap").string() +
                                                  R"(, topics: [/robot/pointz]}
)");
    Process host({kHost, cfg}, (dir_ / "bad").string());
    EXPECT_EQ(host.wait(60), 2);
    EXPECT_NE(host.err().find("no topic '/robot/pointz' in " + (dir_ / "run.mcap").string() +
                              " (topics: /robot/ground_truth, /robot/points)"),
              std::string::npos)
        << host.err();
}
