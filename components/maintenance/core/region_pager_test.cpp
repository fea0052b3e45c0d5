#include "maintenance/core/region_pager.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/core/io_error.hpp"
#include "maintenance/core/long_term_map.hpp"

namespace ltm::maintenance {
namespace {

namespace fs = std::filesystem;

std::string temp_path(const std::string& name) {
    return (fs::temp_directory_path() / ("ltm_pager_" + std::to_string(::getpid()) + "_" + name))
        .string();
}

std::string file_bytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(f)), {});
}

MaintenanceConfig config() {
    MaintenanceConfig c;
    c.view_spacing = 0.0;
    c.view_delay = 2.0;
    return c;
}

// A scan of a 320 m corridor (walls at y = +-8 m, 3 m high) from x, within 40 m of the sensor,
// sensor frame; session 0 also sees a box at x = 60 that is gone in session 1.
std::vector<Eigen::Vector3f> corridor_scan(double x, std::uint32_t session) {
    std::vector<Eigen::Vector3f> pts;
    for (double wx = std::max(0.0, x - 40.0); wx <= std::min(320.0, x + 40.0); wx += 0.5)
        for (int j = 0; j < 12; ++j)
            for (const float y : {-8.0f, 8.0f}) pts.emplace_back(float(wx - x), y, 0.5f * j - 1.0f);
    if (session == 0 && std::abs(x - 60.0) < 30.0)
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 6; ++j)
                pts.emplace_back(float(60.0 - x), -2.0f + 0.25f * i, 0.25f * j - 1.0f);
    return pts;
}

// Drives the corridor out and back in a session; returns the passes' removed voxel counts.
std::vector<std::size_t> drive(LongTermMap& map, std::uint32_t session) {
    std::vector<std::size_t> removed;
    map.begin_session(session, 1000.0 * session);
    int k = 0;
    for (int leg = 0; leg < 2; ++leg) {
        for (double s = 0.0; s <= 300.0; s += 3.0, ++k) {
            const double x = leg == 0 ? s : 300.0 - s;
            Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
            T.translation() = Eigen::Vector3d(x, 0.0, 1.0);
            map.add_scan(corridor_scan(x, session), T, 1000.0 * session + 0.5 * k);
            if (k % 40 == 39) removed.push_back(map.maintain().voxels_removed);
        }
    }
    removed.push_back(map.end_session().voxels_removed);
    return removed;
}

TEST(RegionPager, APagedMapDecidesAndSavesAsOneInMemory) {
    LongTermMap whole(config()), paged(config());
    const std::string dir = temp_path("paged");
    paged.set_paging({60.0, dir});
    for (std::uint32_t session = 0; session < 2; ++session) {
        const std::vector<std::size_t> a = drive(whole, session), b = drive(paged, session);
        EXPECT_EQ(a, b) << "session " << session;
        std::size_t removed = 0;
        for (std::size_t n : a) removed += n;
        if (session == 1) {
            EXPECT_GT(removed, 10u);  // the box that left
        }
    }
    const LongTermMapStats s = paged.stats();
    EXPECT_EQ(s.voxels, whole.stats().voxels);
    EXPECT_EQ(s.regions, whole.stats().regions);
    EXPECT_GT(s.regions_paged, 2u);  // the far end of the corridor is on disk
    EXPECT_GT(s.pages_in, 0u);       // and came back on the way back
    EXPECT_LT(s.memory_bytes, whole.stats().memory_bytes);
    // Session 1 removed the box (the scene is right) and both saves are the same bytes.
    const std::string f1 = temp_path("whole.bin"), f2 = temp_path("paged.bin");
    whole.save(f1);
    paged.save(f2);
    EXPECT_EQ(file_bytes(f1), file_bytes(f2));
    fs::remove(f1);
    fs::remove(f2);
}

TEST(RegionPager, ALoadedMapStartsOnDiskAndComesBackAsItWas) {
    LongTermMap whole(config());
    drive(whole, 0);
    const std::string file = temp_path("loaded.bin"), dir = temp_path("loaded");
    whole.save(file);
    LongTermMap loaded = LongTermMap::load(file, config(), {60.0, dir});
    EXPECT_EQ(loaded.stats().regions_paged, whole.stats().regions);
    EXPECT_EQ(loaded.stats().voxels, whole.stats().voxels);
    EXPECT_TRUE(loaded.voxel_centres().empty());  // nothing in memory yet
    // The next session on both: the same decisions, the same file.
    LongTermMap again = LongTermMap::load(file, config());
    EXPECT_EQ(drive(again, 1), drive(loaded, 1));
    const std::string f1 = temp_path("again1.bin"), f2 = temp_path("again2.bin");
    again.save(f1);
    loaded.save(f2);
    EXPECT_EQ(file_bytes(f1), file_bytes(f2));
    loaded.page_in_all();
    EXPECT_EQ(loaded.stats().regions_paged, 0u);
    EXPECT_EQ(loaded.voxel_centres().size(), again.voxel_centres().size());
    for (const std::string& f : {file, f1, f2}) fs::remove(f);
}

TEST(RegionPager, ARegionAViewJudgedStaysForThePass) {
    LongTermMap map(config());
    map.set_paging({45.0, temp_path("dirty")});
    map.begin_session(0, 0.0);
    int k = 0;
    for (double x = 0.0; x <= 150.0; x += 3.0, ++k) {  // no pass on the way
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(x, 0.0, 1.0);
        map.add_scan(corridor_scan(x, 0), T, 0.5 * k);
    }
    EXPECT_EQ(map.stats().regions_paged, 0u);  // every region waits for its pass in memory
    map.maintain();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(153.0, 0.0, 1.0);
    map.add_scan(corridor_scan(153.0, 0), T, 0.5 * k);
    EXPECT_GT(map.stats().regions_paged, 0u);  // after it, the far ones go
}

TEST(RegionPager, ADamagedPageIsOneLineNotACrash) {
    const std::string dir = temp_path("damaged");
    RegionPager pager(dir, config());
    ObservationMap m(config(), {0, 0});
    m.add_points({{1.0f, 1.0f, 0.0f}, {2.0f, 1.0f, 0.0f}}, 0.0);
    pager.page_out({0, 0}, m);
    ASSERT_TRUE(pager.holds({0, 0}));
    {
        std::fstream f(dir + "/region_0_0.bin", std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(20);
        f.put('\x7f');
    }
    try {
        pager.page_in({0, 0});
        FAIL() << "a damaged page was read";
    } catch (const common::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("region_0_0.bin"), std::string::npos) << e.what();
    }
}

TEST(RegionPager, ARadiusWithoutAFolderIsRefused) {
    LongTermMap map(config());
    EXPECT_THROW(map.set_paging({50.0, ""}), common::ConfigError);
}

}  // namespace
}  // namespace ltm::maintenance
