#pragma once
// Test-only helpers (ltm_registration_test_data) of the verification, places, map, mapping and
// localisation tests: real KITTI scans with their reference poses, synthetic scenes, and local
// maps built from registered scans as the odometry builds them.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/local_map_data.hpp"
#include "common/core/point_cloud.hpp"
#include "common/core/trajectory_io.hpp"

namespace ltm::registration::test {

// KITTI 00 frames 0-15 under ../shared/data, or "" when absent; the repo's 3-frame fixture.
std::string shared_kitti00();
std::string fixture_kitti00();

struct KittiSnippet {
    std::vector<common::PointCloud> scans;  // LiDAR frame
    common::PoseList poses;                 // T_world_lidar (SemanticKITTI poses)
};
// The first `count` scans of a sequence folder (velodyne/, calib.txt, poses_semantickitti.txt).
KittiSnippet load_kitti(const std::string& sequence_dir, std::size_t count);

// Every `stride`-th point starting at `first`.
std::vector<Eigen::Vector3f> every_nth(const std::vector<Eigen::Vector3f>& points,
                                       std::size_t stride, std::size_t first);
// Points p -> T * p.
std::vector<Eigen::Vector3f> transformed(const std::vector<Eigen::Vector3f>& points,
                                         const Eigen::Isometry3d& T);

// A rigid transform from a translation [m] and a yaw [deg].
Eigen::Isometry3d xy_yaw(double x, double y, double yaw_deg);

// A synthetic outdoor scene (world frame): ground, boxes ("buildings") of random size and
// height, poles; fixed seed.
std::vector<Eigen::Vector3f> synthetic_scene(std::uint32_t seed, double extent = 60.0);
// The scene with its ground sampled four times as densely (the synthetic ground alone has too
// few points a 1 m voxel for a normal, which leaves registrations free in z).
std::vector<Eigen::Vector3f> with_dense_ground(const std::vector<Eigen::Vector3f>& scene);
// What a sensor at T_world_lidar sees of it within `range` (no occlusion), in the LiDAR frame.
std::vector<Eigen::Vector3f> view(const std::vector<Eigen::Vector3f>& scene,
                                  const Eigen::Isometry3d& T_world_lidar, double range);

// A local map (voxel g, box half extent) anchored at T_odom_anchor, built by
// integrating each scan (LiDAR frame) at its pose; returned as plain data.
common::LocalMapData build_local_map(std::uint64_t id, const Eigen::Isometry3d& T_odom_anchor,
                                     const std::vector<std::vector<Eigen::Vector3f>>& scans,
                                     const common::PoseList& T_odom_lidar, double voxel_size = 1.0,
                                     double half_extent = 50.0);

}  // namespace ltm::registration::test
