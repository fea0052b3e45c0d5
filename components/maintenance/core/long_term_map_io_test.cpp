#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/core/byte_io.hpp"
#include "common/core/crc32.hpp"
#include "common/core/file_io.hpp"
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
        EXPECT_EQ(a->points.count, b->points.count);
        EXPECT_EQ(a->points.sum_sq, b->points.sum_sq);
        EXPECT_EQ(a->created(), b->created());
        EXPECT_EQ(a->last_point(), b->last_point());
        EXPECT_EQ(a->flags, b->flags);
        EXPECT_EQ(a->hit_histogram().size(), b->hit_histogram().size());
        EXPECT_EQ(histogram_total(a->free_histogram()), histogram_total(b->free_histogram()));
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

// A file of format version 1 (float sums, double times, separate hit and free histograms), as
// the previous build wrote it: one region with two voxels.
std::string version1_file(const MaintenanceConfig& c) {
    common::ByteWriter w;
    w.raw("LTMMAINT", 8);
    w.value(std::uint32_t(1));
    w.section("header", [&](auto& s) {
        s.value(c.voxel_size);
        s.value(c.region_size);
        s.value(c.slot);
        s.value(std::uint32_t(1));  // session
        s.value(200.0);             // session offset
        s.value(260.0);             // now
        s.value(std::uint64_t(7));  // next change
        s.value(std::uint32_t(2));
        s.value(std::uint32_t(0));
        s.value(std::uint32_t(1));
        s.value(std::uint32_t(1));  // regions
    });
    w.section("region", [&](auto& s) {
        s.value(std::int32_t(0));
        s.value(std::int32_t(0));
        s.value(std::uint32_t(2));
        for (int v = 0; v < 2; ++v) {
            s.value(registration::pack_key(10 + v, 20, 4));
            s.value(4.0f);  // weight: four points at +-0.05 m in x around (0.01, 0, 0)
            const float sum[3] = {0.04f, 0.0f, 0.0f};
            for (float x : sum) s.value(x);
            const float sum_sq[6] = {0.01f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
            for (float x : sum_sq) s.value(x);
            s.value(12.5 + v);  // created
            s.value(250.25);    // last point
            s.value(std::uint32_t(0));
            s.value(std::uint8_t(v == 0 ? kGround : 0));
            s.value(std::uint16_t(30));  // hits: 30 slots of 2
            for (int k = 0; k < 30; ++k) {
                s.value(std::int32_t(25 + 2 * k));
                s.value(std::uint16_t(2));
            }
            s.value(std::uint16_t(2));  // free
            s.value(std::int32_t(26));
            s.value(std::uint16_t(1));
            s.value(std::int32_t(500));
            s.value(std::uint16_t(5));
        }
    });
    return std::string(w.bytes().begin(), w.bytes().end());
}

TEST(LongTermMapFile, Version1FilesLoadConverted) {
    MaintenanceConfig c;
    const std::string path = temp_path("v1.bin");
    const std::string bytes = version1_file(c);
    common::write_file_atomic(path, bytes.data(), bytes.size());
    const LongTermMap map = LongTermMap::load(path, c);
    EXPECT_EQ(map.stats().voxels, 2u);
    EXPECT_EQ(map.map_time(), 260.0);
    EXPECT_EQ(map.sessions(), (std::vector<std::uint32_t>{0, 1}));
    const float s = float(c.voxel_size);
    const Eigen::Vector3f cell = (Eigen::Vector3f(10, 20, 4) + Eigen::Vector3f::Constant(0.5f)) * s;
    const ObservedVoxel* v = map.voxel_at(cell);
    ASSERT_NE(v, nullptr);
    EXPECT_EQ(v->flags, kGround);
    EXPECT_EQ(v->created(), 12.5);
    EXPECT_EQ(v->last_point(), 250.25);
    const registration::VoxelSums sums = v->sums(s);
    EXPECT_EQ(sums.weight, 4.0f);
    EXPECT_NEAR(sums.mean().x(), 0.01f, 1e-3f);
    EXPECT_NEAR(sums.sum_sq(0), 0.01f, 1e-4f);
    // 61 views: every one kept, on at most VoxelHistory::kCapacity entries.
    EXPECT_EQ(histogram_total(v->hit_histogram()), 60u);
    EXPECT_EQ(histogram_total(v->free_histogram()), 6u);
    EXPECT_LE(v->history.entries().n, VoxelHistory::kCapacity);
    EXPECT_EQ(v->free_histogram().back().slot, 500) << "the late free views keep their time";
    // And saved again as version 3, it loads the same.
    const std::string again = temp_path("v1_again.bin");
    map.save(again);
    const LongTermMap back = LongTermMap::load(again, c);
    EXPECT_EQ(back.voxel_at(cell)->history.entries().n, v->history.entries().n);
    std::filesystem::remove(path);
    std::filesystem::remove(again);
}

TEST(LongTermMapFile, AnUnknownVersionIsOneLine) {
    MaintenanceConfig c;
    std::string bytes = version1_file(c);
    bytes[8] = 9;  // version 9
    const std::string path = temp_path("v9.bin");
    common::write_file_atomic(path, bytes.data(), bytes.size());
    try {
        (void)LongTermMap::load(path, c);
        FAIL() << "version 9 accepted";
    } catch (const common::IoError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("format version 9"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    std::filesystem::remove(path);
}

// Every field of two voxels, histories included, the same.
void expect_same_voxel(const ObservedVoxel& a, const ObservedVoxel& b) {
    EXPECT_EQ(a.key(), b.key());
    EXPECT_EQ(a.points.count, b.points.count);
    EXPECT_EQ(a.points.sum, b.points.sum);
    EXPECT_EQ(a.points.sum_sq, b.points.sum_sq);
    EXPECT_EQ(a.created_ticks, b.created_ticks);
    EXPECT_EQ(a.last_point_ticks, b.last_point_ticks);
    EXPECT_EQ(a.flags, b.flags);
    const VoxelHistory::Entries ha = a.history.entries(), hb = b.history.entries();
    ASSERT_EQ(ha.n, hb.n);
    EXPECT_EQ(ha.first_hit, hb.first_hit);
    EXPECT_EQ(a.history.hit_span(), b.history.hit_span());
    for (int k = 0; k < ha.n; ++k) {
        EXPECT_EQ(ha.e[std::size_t(k)].slot, hb.e[std::size_t(k)].slot);
        EXPECT_EQ(ha.e[std::size_t(k)].hits, hb.e[std::size_t(k)].hits);
        EXPECT_EQ(ha.e[std::size_t(k)].free, hb.e[std::size_t(k)].free);
    }
}

TEST(LongTermMapFile, CompressedColumnsComeBackBitForBit) {
    const LongTermMap map = small_map();
    const std::string path = temp_path("columns.bin");
    map.save(path);
    const LongTermMap back = LongTermMap::load(path, map.config());
    std::size_t compared = 0;
    for (const Eigen::Vector3f& p : map.voxel_centres()) {
        const ObservedVoxel* a = map.voxel_at(p);
        const ObservedVoxel* b = back.voxel_at(p);
        ASSERT_TRUE(a && b);
        expect_same_voxel(*a, *b);
        ++compared;
    }
    EXPECT_GT(compared, 400u);
    // The file is at most 40 % of the row format's 43 bytes + 8 a history entry.
    std::size_t rows = 0;
    for (const Eigen::Vector3f& p : map.voxel_centres())
        rows += 43 + 8 * std::size_t(map.voxel_at(p)->history.entries().n);
    EXPECT_LT(double(std::filesystem::file_size(path)), 0.4 * double(rows));
    std::filesystem::remove(path);
}

// A region's compressed frame damaged under a correct CRC (what a bug, not the disk, would write)
// is refused in one line, never a crash.
TEST(LongTermMapFile, ADamagedFrameUnderAGoodChecksumIsOneLine) {
    const LongTermMap map = small_map();
    const std::string path = temp_path("frame.bin");
    map.save(path);
    const std::string good = common::read_file(path, path);
    // The first region section: after magic, version and the header section.
    const std::size_t header = 12;
    std::uint32_t header_len = 0;
    std::memcpy(&header_len, good.data() + header, 4);
    const std::size_t region = header + 8 + header_len;
    std::uint32_t len = 0;
    std::memcpy(&len, good.data() + region, 4);
    ASSERT_LT(region + 8 + len, good.size() + 1);
    std::mt19937 rng(11);
    for (int trial = 0; trial < 100; ++trial) {
        std::string bad = good;
        // A byte of the columns' counts or frame (after x, y and the voxel count).
        const std::size_t at =
            region + 4 + 12 + std::uniform_int_distribution<std::size_t>(0, len - 13)(rng);
        bad[at] = char(bad[at] ^ (1 + trial % 255));
        const std::uint32_t crc =
            common::crc32(reinterpret_cast<const std::uint8_t*>(bad.data() + region + 4), len);
        std::memcpy(&bad[region + 4 + len], &crc, 4);
        common::write_file_atomic(path, bad.data(), bad.size());
        try {
            const LongTermMap back = LongTermMap::load(path, map.config());
            // A flipped bit that zstd and the checks cannot see must still be a valid map.
            EXPECT_EQ(back.stats().regions, map.stats().regions);
        } catch (const common::IoError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
    std::filesystem::remove(path);
}

// A file of format version 2 (each voxel as in memory, one after another), as the previous build
// wrote it: one region with two voxels. It loads as written, and saved again (version 3) the same.
TEST(LongTermMapFile, Version2FilesLoad) {
    MaintenanceConfig c;
    common::ByteWriter w;
    w.raw("LTMMAINT", 8);
    w.value(std::uint32_t(2));
    w.section("header", [&](auto& s) {
        s.value(c.voxel_size);
        s.value(c.region_size);
        s.value(c.slot);
        s.value(std::uint32_t(1));  // session
        s.value(200.0);             // session offset
        s.value(260.0);             // now
        s.value(std::uint64_t(7));  // next change
        s.value(std::uint32_t(1));
        s.value(std::uint32_t(1));
        s.value(std::uint32_t(1));  // regions
    });
    w.section("region", [&](auto& s) {
        s.value(std::int32_t(0));
        s.value(std::int32_t(0));
        s.value(std::uint32_t(2));
        for (int v = 0; v < 2; ++v) {
            const registration::VoxelKey key = registration::pack_key(10 + v, 20, 4);
            s.value(std::uint32_t(key));
            s.value(std::uint32_t(key >> 32));
            s.value(std::uint8_t(4));  // points
            for (int k = 0; k < 3; ++k) s.value(std::int16_t(100 * k - 7 * v));
            for (int k = 0; k < 6; ++k) s.value(std::int16_t(30 * k + v));
            s.value(std::uint32_t(200 + v));  // created
            s.value(std::uint32_t(4000));     // last point
            s.value(std::uint8_t(v == 0 ? kGround : 0));
            s.value(std::int32_t(25));         // first hit
            s.value(std::uint16_t(500 - 25));  // span
            s.value(std::uint8_t(3));
            const std::int32_t slots[3] = {25, 26, 500};
            for (int k = 0; k < 3; ++k) {
                s.value(slots[k]);
                s.value(std::uint16_t(k == 1 ? 0 : 2));
                s.value(std::uint16_t(k == 1 ? 3 : 0));
            }
        }
    });
    const std::string path = temp_path("v2.bin");
    common::write_file_atomic(path, w.bytes().data(), w.bytes().size());
    const LongTermMap map = LongTermMap::load(path, c);
    EXPECT_EQ(map.stats().voxels, 2u);
    const float s = float(c.voxel_size);
    const Eigen::Vector3f cell = (Eigen::Vector3f(11, 20, 4) + Eigen::Vector3f::Constant(0.5f)) * s;
    const ObservedVoxel* v = map.voxel_at(cell);
    ASSERT_NE(v, nullptr);
    EXPECT_EQ(v->created_ticks, 201u);
    EXPECT_EQ(v->points.sum_sq[5], 151);
    EXPECT_EQ(v->history.entries().n, 3);
    EXPECT_EQ(v->history.entries().e[2].slot, 500);
    const std::string again = temp_path("v2_again.bin");
    map.save(again);
    const LongTermMap back = LongTermMap::load(again, c);
    expect_same_voxel(*v, *back.voxel_at(cell));
    std::filesystem::remove(path);
    std::filesystem::remove(again);
}

}  // namespace
}  // namespace ltm::maintenance
