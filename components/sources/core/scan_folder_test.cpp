#include "sources/core/scan_folder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/ply_io.hpp"

namespace fs = std::filesystem;
using namespace ltm;

namespace {
const std::string kFixture = std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini";

fs::path temp_dir(const std::string& name) {
    fs::path d =
        fs::temp_directory_path() / ("ltm_scan_folder_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}
}  // namespace

TEST(ScanFolder, KittiFixtureWithTimesAndWindow) {
    sources::ScanFolderConfig cfg;
    cfg.path = kFixture;
    sources::ScanFolder all(cfg);
    ASSERT_EQ(all.size(), 3u);
    EXPECT_NEAR(all.stamp(1), 0.1037359, 1e-7);
    EXPECT_EQ(all.load(2).size(), 31120u);
    EXPECT_NEAR(all.load(2).stamp, all.stamp(2), 1e-12);
    cfg.start = 1;
    cfg.count = 1;
    sources::ScanFolder one(cfg);
    ASSERT_EQ(one.size(), 1u);
    EXPECT_NEAR(one.stamp(0), 0.1037359, 1e-7);
    cfg.start = 5;
    EXPECT_THROW(sources::ScanFolder bad(cfg), common::IoError);
}

TEST(ScanFolder, CloudFilesWithPosesAndDefaultPeriod) {
    const fs::path d = temp_dir("ply");
    common::PoseList poses;
    std::string pose_text;
    for (int i = 0; i < 3; ++i) {
        common::PlyCloud c;
        c.points = {{float(i), 0, 0}, {0, 1, 0}};
        char name[32];
        std::snprintf(name, sizeof name, "%06d.ply", i);
        common::write_ply((d / name).string(), c);
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation().x() = i;
        pose_text += common::format_kitti_pose(T);
    }
    std::ofstream(d / "poses.txt") << pose_text;
    sources::ScanFolderConfig cfg;
    cfg.path = d.string();
    cfg.format = sources::ScanFormat::kCloudFiles;
    cfg.poses_file = (d / "poses.txt").string();
    cfg.default_period_s = 0.5;
    sources::ScanFolder f(cfg);
    ASSERT_EQ(f.size(), 3u);
    ASSERT_TRUE(f.has_poses());
    EXPECT_DOUBLE_EQ(f.pose(2).translation().x(), 2.0);
    EXPECT_DOUBLE_EQ(f.stamp(2), 1.0);
    EXPECT_EQ(f.load(1).points[0].x(), 1.0f);
    // Too few poses for the scans: refused with the counts.
    std::ofstream(d / "short.txt") << common::format_kitti_pose(Eigen::Isometry3d::Identity());
    cfg.poses_file = (d / "short.txt").string();
    try {
        sources::ScanFolder bad(cfg);
        FAIL();
    } catch (const common::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("1 poses for 3 scans"), std::string::npos);
    }
    fs::remove_all(d);
}

TEST(ScanFolder, AutoDetectsTheLayout) {
    sources::ScanFolderConfig cfg;
    cfg.path = kFixture;
    cfg.format = sources::ScanFormat::kAuto;
    sources::ScanFolder kitti(cfg);
    EXPECT_EQ(kitti.format(), sources::ScanFormat::kKittiBin);
    EXPECT_TRUE(kitti.has_times());
    const fs::path d = temp_dir("auto");
    common::PlyCloud c;
    c.points = {{1, 2, 3}};
    common::write_ply((d / "a.ply").string(), c);
    cfg.path = d.string();
    sources::ScanFolder clouds(cfg);
    EXPECT_EQ(clouds.format(), sources::ScanFormat::kCloudFiles);
    EXPECT_FALSE(clouds.has_times());
    fs::remove_all(d);
}

TEST(ScanFolder, TimesGoingBackwardsAreRefused) {
    const fs::path d = temp_dir("times");
    fs::create_directories(d / "velodyne");
    common::PointCloud c;
    c.points = {{1, 2, 3}};
    for (int i = 0; i < 3; ++i)
        common::write_kitti_bin((d / "velodyne" / ("00000" + std::to_string(i) + ".bin")).string(),
                                c);
    std::ofstream(d / "times.txt") << "0.0\n0.2\n0.1\n";
    sources::ScanFolderConfig cfg;
    cfg.path = d.string();
    EXPECT_THROW(sources::ScanFolder f(cfg), common::IoError);
    fs::remove_all(d);
}

namespace {
// An ASCII PCD of three points with x y z and, after them, the given fields and values.
void write_pcd(const fs::path& path, const std::string& fields, const std::string& sizes,
               const std::string& types, const std::vector<std::string>& extra) {
    std::ofstream out(path);
    out << "VERSION 0.7\nFIELDS x y z" << fields << "\nSIZE 4 4 4" << sizes << "\nTYPE F F F"
        << types << "\nCOUNT 1 1 1";
    for (std::size_t k = 0; k < fields.size(); ++k)
        if (fields[k] == ' ') out << " 1";
    out << "\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA ascii\n";
    for (int i = 0; i < 3; ++i)
        out << i + 1 << " 0 0" << (extra.empty() ? "" : " ") << (extra.empty() ? "" : extra[i])
            << "\n";
}
}  // namespace

// Per-point time from PCD fields: float seconds, integer nanoseconds, absolute times made
// relative to the stamp from times.txt; no field, no times.
TEST(ScanFolder, CloudFilesKeepPerPointTime) {
    const fs::path d = temp_dir("pcd_time");
    fs::create_directories(d / "Scans");
    write_pcd(d / "Scans" / "000000.pcd", " intensity t", " 4 4", " F F",
              {"0.5 0", "0.25 0.0125", "0.75 0.09975"});
    write_pcd(d / "Scans" / "000001.pcd", " intensity", " 4", " F", {"0.5", "0.25", "0.75"});
    write_pcd(d / "Scans" / "000002.pcd", " t", " 4", " U", {"0", "50000000", "99000000"});
    write_pcd(d / "Scans" / "000003.pcd", " timestamp", " 8", " F",
              {"1700000000.200000", "1700000000.250000", "1700000000.299000"});
    write_pcd(d / "Scans" / "000004.pcd", " time", " 4", " F", {"0", "25", "50"});
    std::ofstream(d / "times.txt") << "1700000000.0\n1700000000.1\n1700000000.2\n1700000000.3\n"
                                      "1700000000.4\n";
    sources::ScanFolderConfig cfg;
    cfg.path = d.string();
    cfg.format = sources::ScanFormat::kAuto;
    const sources::ScanFolder f(cfg);
    ASSERT_EQ(f.size(), 5u);
    const common::PointCloud with_t = f.load(0);
    ASSERT_TRUE(with_t.has_time());
    EXPECT_EQ(with_t.time, (std::vector<float>{0.0f, 0.0125f, 0.09975f}));
    EXPECT_EQ(with_t.intensity, (std::vector<float>{0.5f, 0.25f, 0.75f}));
    EXPECT_DOUBLE_EQ(with_t.stamp, 1700000000.0);
    EXPECT_FALSE(f.load(1).has_time());
    const common::PointCloud ns = f.load(2);  // uint32 nanoseconds, as Ouster's t
    ASSERT_EQ(ns.time.size(), 3u);
    EXPECT_FLOAT_EQ(ns.time[1], 0.05f);
    EXPECT_FLOAT_EQ(ns.time[2], 0.099f);
    const common::PointCloud absolute = f.load(3);  // float64 seconds since 1970
    ASSERT_EQ(absolute.time.size(), 3u);
    EXPECT_NEAR(absolute.time[0], -0.1, 1e-6);
    EXPECT_NEAR(absolute.time[2], -0.001, 1e-6);
    // Seconds that cannot be a sweep's (here milliseconds in a float field): one line.
    try {
        f.load(4);
        FAIL();
    } catch (const common::IoError& e) {
        EXPECT_NE(std::string(e.what()).find("per-point times reach 50 s"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("000004.pcd"), std::string::npos) << e.what();
    }
    // Absolute times without a times.txt to relate them to: refused, not mangled.
    fs::remove(d / "times.txt");
    const sources::ScanFolder no_times(cfg);
    EXPECT_THROW(no_times.load(3), common::IoError);
    EXPECT_EQ(no_times.load(2).time.size(), 3u);
    fs::remove_all(d);
}
