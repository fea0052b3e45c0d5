// The maintenance component through the host: session 0 of the tiny simulated site (a service car
// driving back and forth, two pedestrians) at its true poses; a probe component of the test host
// writes what the component publishes. Every pass leaves its change record, the summary and the
// PLY in the output folder, which the component creates; the maintained map is saved and carries
// over to the next run; odd scans (empty, NaN points) are fine and a bad parameter is one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "host/launch_paths.hpp"
#include "host/process.hpp"
#include "host/temp_dir_test.hpp"
#include "maintenance/core/change_ledger.hpp"
#include "maintenance/core/change_record.hpp"
#include "maintenance/core/long_term_map.hpp"

namespace fs = std::filesystem;
using ltm::tests::kHost;
using ltm::tests::kTestHost;
using ltm::tests::Process;
using namespace ltm;

namespace {

const std::string kScenario = ltm::tests::scenario("tiny_loop.yaml");

std::string header(int domain) {
    return ltm::tests::launch_header(domain, "/robot", "points: stream, ground_truth: stream");
}

struct Published {
    std::size_t pass = 0, changes = 0, voxels = 0;
    std::string frame;
};

std::vector<Published> read_probe(const fs::path& file, std::vector<std::string>* events) {
    std::vector<Published> out;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        std::istringstream ss(line);
        std::string kind;
        ss >> kind;
        if (kind == "changes") {
            Published p;
            double stamp = 0, voxel = 0;
            unsigned session = 0;
            ss >> stamp >> p.frame >> p.pass >> session >> voxel >> p.changes >> p.voxels;
            out.push_back(p);
        } else if (kind == "event" && events) {
            std::string rest;
            std::getline(ss >> std::ws, rest);
            events->push_back(rest);
        }
    }
    return out;
}

class MaintenancePipeline : public ltm::tests::TempDirTest {
  protected:
    MaintenancePipeline() : TempDirTest("ltm_maintenance_") {}
};

}  // namespace

// The car and the pedestrians leave the map (the pass at shutdown, once every view judged): a pass
// publishes its changes, in the poses' frame; every pass (every 4 s and at shutdown) wrote a
// record that reads back and applies, one summary per pass, and the PLY of every change.
TEST_F(MaintenancePipeline, PublishesMapChangesAndWritesTheReport) {
    const std::string out = path("reports/session0");  // created by the component
    const std::string cfg = write("maintain.yaml", header(222) + R"(  - name: sensor
    type: simulator
    params: {scenario: )" + kScenario + R"(, mode: fast, session: 0}
  - name: maintenance
    type: maintenance
    params: {input: pose, output_dir: )" + out + R"(, maintain_every_s: 4}
    remap: {pose: ground_truth}
  - name: probe
    type: test_map_changes_probe
    params: {file: )" + path("probe.txt") + R"(}
)");
    Process host({kTestHost, cfg}, path("host"));
    ASSERT_EQ(host.wait(120), 0) << host.err();
    std::vector<std::string> events;
    const std::vector<Published> published = read_probe(dir_ / "probe.txt", &events);
    ASSERT_FALSE(published.empty()) << host.err();
    std::size_t published_voxels = 0;
    for (const Published& p : published) {
        EXPECT_EQ(p.frame, "world");
        EXPECT_GT(p.changes, 0u);
        published_voxels += p.voxels;
    }
    // The records: passes 0, 1, ... in order; those with changes are the ones published.
    maintenance::ChangeLedger ledger(0.25f);
    std::size_t records = 0, with_changes = 0, voxels = 0;
    for (;; ++records) {
        char name[32];
        std::snprintf(name, sizeof name, "changes_%04zu.ltmc", records);
        if (!fs::exists(fs::path(out) / name)) break;
        const maintenance::ChangeSet c =
            maintenance::read_change_record((fs::path(out) / name).string());
        EXPECT_EQ(c.session, 0u);
        with_changes += !c.changes.empty();
        for (const auto& s : c.changes) voxels += s.voxels.size();
        ledger.apply(c);
    }
    EXPECT_GE(records, 2u) << "a pass every 4 s of the 8 s session, and one at shutdown";
    EXPECT_EQ(with_changes, published.size());
    EXPECT_EQ(voxels, published_voxels);
    EXPECT_GT(ledger.removed_voxels(), 0u);
    // The summary: a line per pass; the PLY: every changed voxel.
    std::ifstream summary(fs::path(out) / "changes.txt");
    std::size_t pass_lines = 0;
    for (std::string line; std::getline(summary, line);)
        pass_lines += line.rfind("session 0 pass ", 0) == 0;
    EXPECT_EQ(pass_lines, records);
    std::ifstream ply(fs::path(out) / "changes_removed_added.ply", std::ios::binary);
    const std::string head((std::istreambuf_iterator<char>(ply)), std::istreambuf_iterator<char>());
    EXPECT_NE(head.find("element vertex " + std::to_string(voxels) + "\n"), std::string::npos);
    // A line on `status` for every pass.
    std::size_t said = 0;
    for (const std::string& e : events) said += e.rfind("maintenance 0 maintained pass ", 0) == 0;
    EXPECT_EQ(said, records);
}

// An empty scan and one of NaN points only, then scans of a wall with a NaN among them: every scan
// with a pose is taken, nothing fails; the scan whose pose never came is counted, not waited for.
TEST_F(MaintenancePipeline, EmptyAndNanScansAreFine) {
    const std::string cfg = write("odd.yaml", header(223) + R"(  - name: source
    type: test_odd_scans_source
    params: {scans: 6, no_pose: 4}
  - name: maintenance
    type: maintenance
    params: {input: pose, output_dir: )" + path("out") +
                                                  R"(, maintain_every_s: 0}
)");
    Process host({kTestHost, cfg}, path("host"));
    ASSERT_EQ(host.wait(60), 0) << host.err();
    EXPECT_NE(host.err().find("8 scans: 7 maintained, 1 without a pose"), std::string::npos)
        << host.err();
    EXPECT_EQ(host.err().find("maintenance_failed"), std::string::npos) << host.err();
    EXPECT_TRUE(fs::exists(path("out/changes_0000.ltmc")));
}

// The maintained map carries over: a second run on the map file the first saved is session 1 on it;
// a damaged map file refuses the component in one line (the host does not start) and stays as it
// was, not overwritten.
TEST_F(MaintenancePipeline, TheSavedMapCarriesOverAndADamagedOneIsRefused) {
    const std::string map = path("maps/long_term_map.bin");  // its folder created
    const auto run = [&](int domain) {
        return write("run.yaml", header(domain) + R"(  - name: source
    type: test_odd_scans_source
    params: {scans: 3}
  - name: maintenance
    type: maintenance
    params: {input: pose, map_file: )" +
                                     map + R"(, maintain_every_s: 0}
)");
    };
    Process first({kTestHost, run(225)}, path("first"));
    ASSERT_EQ(first.wait(60), 0) << first.err();
    const maintenance::MaintenanceConfig config;
    const maintenance::LongTermMap once = maintenance::LongTermMap::load(map, config);
    EXPECT_EQ(once.sessions(), std::vector<std::uint32_t>{0});
    EXPECT_GT(once.stats().voxels, 0u);
    Process second({kTestHost, run(225)}, path("second"));
    ASSERT_EQ(second.wait(60), 0) << second.err();
    EXPECT_NE(second.err().find("map " + map + ": "), std::string::npos) << second.err();
    const maintenance::LongTermMap twice = maintenance::LongTermMap::load(map, config);
    EXPECT_EQ(twice.sessions(), (std::vector<std::uint32_t>{0, 1}));

    std::string bytes;
    {
        std::ifstream in(map, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    ASSERT_GT(bytes.size(), 100u);
    bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x20);
    std::ofstream(map, std::ios::binary | std::ios::trunc) << bytes;
    Process damaged({kTestHost, run(225)}, path("damaged"));
    EXPECT_EQ(damaged.wait(60), 2);
    const std::string err = damaged.err();
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find("maintenance.map_file: " + map + ": "), std::string::npos) << err;
    std::ifstream in(map, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()),
              bytes);
}

// A bad parameter stops the host before it starts, with one line naming the file, line and key.
TEST_F(MaintenancePipeline, BadParameterIsOneLine) {
    const std::string cfg = write("bad.yaml", header(224) + R"(  - name: maintenance
    type: maintenance
    params: {input: pose, change: {sigma: -1}}
)");
    Process host({kHost, cfg}, path("host"));
    EXPECT_EQ(host.wait(30), 2);
    const std::string err = host.err();
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find(cfg + ":8: maintenance.change.sigma: "), std::string::npos) << err;
}
