#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/core/io_error.hpp"
#include "maintenance/core/long_term_map.hpp"

namespace ltm::maintenance {
namespace {

// A small map: two sessions of a few synthetic scans of a wall and a box.
LongTermMap small_map() {
    MaintenanceConfig c;
    c.view_spacing = 0.0;
    LongTermMap map(c);
    for (std::uint32_t session = 0; session < 2; ++session) {
        map.begin_session(session, 100.0 * session);
        for (int k = 0; k < 6; ++k) {
            std::vector<Eigen::Vector3f> pts;
            for (int i = 0; i < 40; ++i)
                for (int j = 0; j < 12; ++j) pts.emplace_back(8.0f, -5.0f + 0.25f * i, 0.25f * j);
            if (session == 0)
                for (int i = 0; i < 8; ++i) pts.emplace_back(4.0f, 0.2f * i, 0.5f);
            Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
            T.translation() = Eigen::Vector3d(0.3 * k, 45.0 * session, 1.0);
            map.add_scan(pts, T, 100.0 * session + 0.2 * k);
        }
        map.end_session();
    }
    return map;
}

std::string temp_path(const std::string& name) {
    return (std::filesystem::temp_directory_path() /
            ("ltm_maint_" + std::to_string(::getpid()) + "_" + name))
        .string();
}

TEST(LongTermMapFile, RoundTripKeepsEveryVoxelAndTheClock) {
    const LongTermMap map = small_map();
    const std::string path = temp_path("round.bin");
    map.save(path);
    const LongTermMap back = LongTermMap::load(path, map.config());
    EXPECT_EQ(back.stats().voxels, map.stats().voxels);
    EXPECT_EQ(back.stats().regions, map.stats().regions);
    EXPECT_EQ(back.map_time(), map.map_time());
    EXPECT_EQ(back.sessions(), (std::vector<std::uint32_t>{0, 1}));
    for (const Eigen::Vector3f& p : map.voxel_centres()) {
        const ObservedVoxel* a = map.voxel_at(p);
        const ObservedVoxel* b = back.voxel_at(p);
        ASSERT_TRUE(a && b);
        EXPECT_EQ(a->sums.weight, b->sums.weight);
        EXPECT_EQ(a->created, b->created);
        EXPECT_EQ(a->hits.size(), b->hits.size());
        EXPECT_EQ(histogram_total(a->free), histogram_total(b->free));
    }
    // Saved again, byte for byte the same.
    const std::string again = temp_path("again.bin");
    back.save(again);
    std::ifstream f1(path, std::ios::binary), f2(again, std::ios::binary);
    const std::string b1((std::istreambuf_iterator<char>(f1)), {}),
        b2((std::istreambuf_iterator<char>(f2)), {});
    EXPECT_EQ(b1, b2);
    std::filesystem::remove(path);
    std::filesystem::remove(again);
}

TEST(LongTermMapFile, DamageIsOneLineNeverACrash) {
    const LongTermMap map = small_map();
    const std::string path = temp_path("damage.bin");
    map.save(path);
    std::ifstream f(path, std::ios::binary);
    const std::string good((std::istreambuf_iterator<char>(f)), {});
    f.close();
    std::mt19937 rng(5);
    const std::string bad_path = temp_path("bad.bin");
    for (int trial = 0; trial < 200; ++trial) {
        std::string bad = good;
        if (trial % 4 == 0) {
            bad.resize(std::uniform_int_distribution<std::size_t>(0, good.size() - 1)(rng));
        } else {
            const std::size_t at =
                std::uniform_int_distribution<std::size_t>(0, good.size() - 1)(rng);
            bad[at] = char(bad[at] ^ (1 + trial % 255));
        }
        std::ofstream(bad_path, std::ios::binary) << bad;
        try {
            (void)LongTermMap::load(bad_path, map.config());
            ADD_FAILURE() << "damage accepted, trial " << trial;
        } catch (const common::IoError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
    MaintenanceConfig other = map.config();
    other.voxel_size = 0.3;
    try {
        (void)LongTermMap::load(path, other);
        FAIL() << "another voxel size accepted";
    } catch (const common::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("voxel_size"), std::string::npos) << e.what();
    }
    EXPECT_THROW(LongTermMap::load(temp_path("missing.bin"), map.config()), common::IoError);
    std::filesystem::remove(path);
    std::filesystem::remove(bad_path);
}

}  // namespace
}  // namespace ltm::maintenance
