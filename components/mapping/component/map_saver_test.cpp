// The mapping's saves (map_saver.hpp): a background save never writes an older map over a newer
// one, a stop finishes the save that waits, a failure is said and asked again, and a save that
// must be done now does not wait for the budget a background one is waiting for.
#include "mapping/component/map_saver.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "common/core/thread_clock.hpp"

namespace ltm::mapping {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
    const fs::path p = fs::temp_directory_path() / ("ltm_map_saver_" + name);
    fs::remove_all(p);
    return p;
}

// A map of `maps` local maps in a row (a few thousand voxels each), at revision `revision`.
map::MapData small_map(std::uint64_t revision, int maps) {
    map::MapData m;
    m.revision = revision;
    for (int n = 0; n < maps; ++n) {
        map::PoseGraphNode node;
        node.id = std::uint64_t(n);
        node.local_map_id = std::uint64_t(n);
        node.T_odom_anchor.translation() = Eigen::Vector3d(20.0 * n, 0, 0);
        node.T_world_anchor = node.T_odom_anchor;
        node.fixed = n == 0;
        m.nodes.push_back(node);
        auto data = std::make_shared<common::LocalMapData>();
        data->id = std::uint64_t(n);
        data->revision = revision;
        data->voxel_size = 0.5f;
        for (int i = 0; i < 4000; ++i) {
            common::VoxelData v;
            v.index = Eigen::Vector3i(i % 40, (i / 40) % 40, i / 1600);
            v.centre = v.index.cast<float>() * 0.5f;
            v.normal = Eigen::Vector3f::UnitZ();
            v.point_count = 3;
            data->voxels.push_back(v);
        }
        m.local_maps.push_back({node.id, 0, data});
    }
    for (int n = 1; n < maps; ++n) {
        map::PoseGraphEdge e;
        e.from = std::uint64_t(n - 1);
        e.to = std::uint64_t(n);
        e.T_from_to.translation() = Eigen::Vector3d(20.0, 0, 0);
        e.information = map::Matrix6d::Identity();
        m.edges.push_back(e);
    }
    return m;
}

std::uint64_t saved_revision(const fs::path& dir) {
    return map::load_map(dir.string()).map.revision;
}

struct Lines {
    std::vector<std::pair<bool, std::string>> lines;
    std::mutex mutex;
    std::function<void(bool, const std::string&)> sink() {
        return [this](bool ok, const std::string& line) {
            std::lock_guard<std::mutex> lock(mutex);
            lines.emplace_back(ok, line);
        };
    }
};

TEST(MapSaver, AWaitingSaveOlderThanASaveNowIsSkipped) {
    const fs::path dir = fresh_dir("older");
    Lines log;
    MapSaver saver("mapping", dir.string(), {}, nullptr, log.sink());
    saver.save_in_background(small_map(1, 2), {});  // waits: the thread is not started yet
    saver.save_now(small_map(2, 3), {});
    saver.start();
    saver.stop();
    EXPECT_EQ(saved_revision(dir), 2u);
    EXPECT_EQ(saver.skipped(), 1u);
    EXPECT_EQ(saver.background_saves(), 0u);
}

// A staging emptied behind the saver's back (a lifelong session's site component, constructed
// after the mapping, removed what the mapping's first save had put there): the saver no longer
// names those files as written, so the mapping does not page a local map out onto a file that is
// gone; the next save writes them again.
TEST(MapSaver, FilesGoneFromTheFolderAreNotNamedAsWrittenAndTheNextSaveWritesThemAgain) {
    const fs::path dir = fresh_dir("gone");
    Lines log;
    MapSaver saver("mapping", dir.string(), {}, nullptr, log.sink());
    const map::MapData m = small_map(1, 3);
    saver.save_now(m, {});
    EXPECT_EQ(saver.written_local_maps().size(), 3u);
    fs::remove_all(dir);
    EXPECT_TRUE(saver.written_local_maps().empty());
    saver.save_now(m, {});  // the same map: the writer sees its files gone and writes them
    EXPECT_EQ(saver.written_local_maps().size(), 3u);
    const map::LoadedMap back = map::load_map(dir.string());
    EXPECT_TRUE(back.refused.empty());
    EXPECT_EQ(back.map.local_maps.size(), 3u);
}

TEST(MapSaver, AStopFinishesTheSaveThatWaits) {
    const fs::path dir = fresh_dir("stop");
    Lines log;
    MapSaver saver("mapping", dir.string(), {}, nullptr, log.sink());
    saver.start();
    saver.save_in_background(small_map(3, 3), {});
    saver.stop();
    EXPECT_EQ(saved_revision(dir), 3u);
    EXPECT_EQ(saver.background_saves(), 1u);
    ASSERT_EQ(log.lines.size(), 1u);
    EXPECT_TRUE(log.lines[0].first);
    EXPECT_EQ(log.lines[0].second.rfind("map saved to " + dir.string(), 0), 0u)
        << log.lines[0].second;
}

TEST(MapSaver, AFailedBackgroundSaveIsSaidAndAskedForAgain) {
    const fs::path file = fresh_dir("not_a_dir");
    std::ofstream(file) << "a file where the map's folder should be";
    Lines log;
    MapSaver saver("mapping", file.string(), {}, nullptr, log.sink());
    saver.start();
    saver.save_in_background(small_map(1, 1), {});
    saver.stop();
    ASSERT_EQ(log.lines.size(), 1u);
    EXPECT_FALSE(log.lines[0].first);
    EXPECT_EQ(log.lines[0].second.rfind("map not saved: ", 0), 0u) << log.lines[0].second;
    EXPECT_EQ(log.lines[0].second.find('\n'), std::string::npos);
    EXPECT_TRUE(saver.take_failed());
    EXPECT_FALSE(saver.take_failed());  // said once
    fs::remove(file);
}

// The budget deep in debt: a background save waits after its first file for hours. A save that
// must be done now (a request, the shutdown) ends that wait and writes the newer map; the
// background one then does not write the older one over it. Without the hurry this test hangs
// (ctest's timeout fails it).
TEST(MapSaver, ASaveNowDoesNotWaitForTheBudget) {
    const fs::path dir = fresh_dir("hurry");
    auto budget = std::make_shared<common::CpuBudget>(0.01, 0.0);
    budget->charge(1000.0, common::steady_wall_s());  // 1000 s of CPU owed: 28 h at 1 %
    Lines log;
    MapSaver saver("mapping", dir.string(), {}, budget, log.sink());
    saver.start();
    saver.save_in_background(small_map(1, 4), {});
    // Until the background save has written a file and waits for the budget.
    for (int i = 0; i < 1000 && saver.longest_piece_s() <= 0.0; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_GT(saver.longest_piece_s(), 0.0) << "the background save never wrote a file";
    saver.save_now(small_map(2, 2), {});
    EXPECT_EQ(saved_revision(dir), 2u);
    saver.stop();
    EXPECT_EQ(saved_revision(dir), 2u);
}

}  // namespace
}  // namespace ltm::mapping
