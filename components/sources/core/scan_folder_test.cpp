#include "sources/core/scan_folder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

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
