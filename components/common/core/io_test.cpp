#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/core/io_error.hpp"
#include "common/core/kitti_io.hpp"
#include "common/core/pcl_cloud_io.hpp"
#include "common/core/ply_io.hpp"
#include "common/core/trajectory_io.hpp"

namespace fs = std::filesystem;
using namespace ltm::common;

namespace {

fs::path temp_dir(const std::string& name) {
    fs::path d =
        fs::temp_directory_path() / ("ltm_io_test_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

const std::string kFixture = std::string(LTM_SOURCE_DIR) + "/tests/fixtures/kitti00_mini";

}  // namespace

TEST(KittiIo, ReadsTheRealFixture) {
    const auto scans = list_kitti_scans(kFixture);
    ASSERT_EQ(scans.size(), 3u);
    const PointCloud c = read_kitti_bin(scans[0]);
    EXPECT_EQ(c.size(), 31167u);
    EXPECT_TRUE(c.has_intensity());
    EXPECT_EQ(read_times(kFixture + "/times.txt").size(), 3u);
    const Eigen::Isometry3d Tr = read_kitti_calib_tr(kFixture + "/calib.txt");
    EXPECT_NEAR(Tr.matrix()(0, 1), -9.999672484946e-01, 1e-12);
    EXPECT_EQ(kitti_sequence_dir(kFixture + "/velodyne"), kFixture);
}

TEST(KittiIo, BinRoundTripAndTruncatedFile) {
    const fs::path d = temp_dir("bin");
    PointCloud c;
    c.points = {{1, 2, 3}, {4, 5, 6}};
    c.intensity = {0.5f, 0.25f};
    write_kitti_bin((d / "a.bin").string(), c);
    const PointCloud r = read_kitti_bin((d / "a.bin").string());
    EXPECT_EQ(r.points, c.points);
    EXPECT_EQ(r.intensity, c.intensity);
    fs::resize_file(d / "a.bin", 20);
    try {
        read_kitti_bin((d / "a.bin").string());
        FAIL() << "truncated file accepted";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("not a multiple of 16"), std::string::npos);
    }
    EXPECT_THROW(read_kitti_bin((d / "missing.bin").string()), IoError);
    fs::remove_all(d);
}

TEST(TrajectoryIo, KittiAndTumRoundTrip) {
    const fs::path d = temp_dir("traj");
    Trajectory traj;
    for (int i = 0; i < 4; ++i) {
        StampedPose sp;
        sp.stamp = 0.1 * i;
        sp.pose = Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(0.2, 0.3, 1).normalized());
        sp.pose.translation() = Eigen::Vector3d(i, -2.0 * i, 0.5);
        traj.push_back(sp);
    }
    PoseList poses;
    for (const auto& sp : traj) poses.push_back(sp.pose);
    write_kitti_poses((d / "k.txt").string(), poses);
    write_tum_trajectory((d / "t.txt").string(), traj);
    const PoseList k = read_kitti_poses((d / "k.txt").string());
    const Trajectory t = read_tum_trajectory((d / "t.txt").string());
    ASSERT_EQ(k.size(), 4u);
    ASSERT_EQ(t.size(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_TRUE(k[i].isApprox(poses[i], 1e-8));
        EXPECT_TRUE(t[i].pose.isApprox(poses[i], 1e-8));
        EXPECT_NEAR(t[i].stamp, 0.1 * i, 1e-9);
    }
    std::ofstream(d / "bad.txt") << "1 0 0 0\n";
    try {
        read_kitti_poses((d / "bad.txt").string());
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("line 1"), std::string::npos);
    }
    fs::remove_all(d);
}

TEST(TrajectoryIo, CameraToLidarMatchesDefinition) {
    Eigen::Isometry3d Tr = Eigen::Isometry3d::Identity();
    Tr.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    Tr.translation() = Eigen::Vector3d(0.1, 0.2, 0.3);
    Eigen::Isometry3d P = Eigen::Isometry3d::Identity();
    P.translation() = Eigen::Vector3d(0, 0, 5);  // camera moves 5 m along its z
    const PoseList out = camera_to_lidar_poses({P}, Tr);
    EXPECT_TRUE(out[0].isApprox(Tr.inverse() * P * Tr));
    // The camera's forward z axis is the LiDAR's -y here: the LiDAR moved 5 m along its y... sign
    // check:
    EXPECT_NEAR(out[0].translation().norm(), 5.0, 1e-12);
}

TEST(PlyIo, CloudAndMeshAreReadableByPcl) {
    const fs::path d = temp_dir("ply");
    PlyCloud cloud;
    cloud.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    cloud.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    cloud.intensity = {1, 2, 3};
    write_ply((d / "c.ply").string(), cloud);
    const PointCloud back = load_cloud_file((d / "c.ply").string());
    ASSERT_EQ(back.size(), 3u);
    EXPECT_EQ(back.points[1], Eigen::Vector3f(1, 0, 0));
    EXPECT_EQ(back.intensity[2], 3.0f);

    PlyMesh mesh;
    mesh.vertices = cloud.points;
    mesh.triangles = {{0, 1, 2}};
    write_ply((d / "m.ply").string(), mesh);
    EXPECT_EQ(load_cloud_file((d / "m.ply").string()).size(), 3u);
    mesh.triangles = {{0, 1, 3}};
    EXPECT_THROW(write_ply((d / "bad.ply").string(), mesh), IoError);
    EXPECT_FALSE(fs::exists(d / "bad.ply"));
    fs::remove_all(d);
}

TEST(PclIo, MalformedAndMissingFilesGiveOneLine) {
    const fs::path d = temp_dir("pcl");
    std::ofstream(d / "junk.pcd") << "this is not a pcd file\n";
    EXPECT_THROW(load_cloud_file((d / "junk.pcd").string()), IoError);
    EXPECT_THROW(load_cloud_file((d / "none.pcd").string()), IoError);
    std::ofstream(d / "junk.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n";
    EXPECT_THROW(load_cloud_file((d / "junk.ply").string()), IoError);
    // A binary PCD whose data stops early.
    std::ofstream(d / "short.pcd")
        << "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
           "WIDTH 10\nHEIGHT 1\nPOINTS 10\nDATA binary\n1234";
    try {
        load_cloud_file((d / "short.pcd").string());
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos);
    }
    std::ofstream(d / "x.txt") << "1 2 3\n";
    EXPECT_THROW(load_cloud_file((d / "x.txt").string()), IoError);
    fs::remove_all(d);
}
