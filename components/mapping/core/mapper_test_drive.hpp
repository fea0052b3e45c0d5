#pragma once
// Test helpers of the Mapper's long-term tests (mapper_long_term_test.cpp, mapper_paging_test.cpp):
// a synthetic road driven in keyframes and local maps, and its replay into a Mapper.
#include <gtest/gtest.h>

#include <vector>

#include "mapping/core/mapper.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping::test {

// A synthetic road driven east along y = 0: keyframes every 3 m, local maps of 4 keyframes (12 m
// apart), each map finished after its last keyframe.
struct Drive {
    std::vector<Eigen::Vector3f> scene;
    common::PoseList truth, odom;
    std::vector<std::vector<Eigen::Vector3f>> points;
    std::vector<common::LocalMapData> maps;
    double t0 = 0.0;
    std::uint64_t first_map = 0;  // local map ids first_map .. first_map + 3

    // Keyframe i at x = x0 + 3 i, y = y0 in the world (westward: x = x0 - 3 i, heading west);
    // the odometry frame is T_odom_world and, from keyframe `jump_at` on, off by `jump` more (an
    // odometry error at a map switch).
    Drive(const std::vector<Eigen::Vector3f>& s, double x0, double y0,
          const Eigen::Isometry3d& T_odom_world, double start, std::size_t jump_at = 1000,
          const Eigen::Isometry3d& jump = Eigen::Isometry3d::Identity(), std::uint64_t map0 = 0,
          bool westward = false)
        : scene(s), t0(start), first_map(map0) {
        for (std::size_t i = 0; i < 16; ++i) {
            truth.push_back(registration::test::xy_yaw(x0 + (westward ? -3.0 : 3.0) * double(i), y0,
                                                       westward ? 180.0 : 0.0));
            odom.push_back((i >= jump_at ? jump : Eigen::Isometry3d::Identity()) * T_odom_world *
                           truth.back());
            points.push_back(registration::test::view(scene, truth.back(), 50.0));
        }
        for (std::uint64_t m = 0; m < 4; ++m) {
            std::vector<std::vector<Eigen::Vector3f>> scans(points.begin() + 4 * m,
                                                            points.begin() + 4 * m + 4);
            common::PoseList poses(odom.begin() + 4 * m, odom.begin() + 4 * m + 4);
            maps.push_back(
                registration::test::build_local_map(first_map + m, poses.front(), scans, poses));
            // Stamped in this drive's time.
            for (double& t : maps.back().observation_times) t += start;
            for (common::VoxelData& v : maps.back().voxels) {
                v.life.created += start;
                v.life.last_seen += start;
            }
        }
    }

    common::KeyframeData keyframe(std::size_t i) const {
        common::KeyframeData k;
        k.id = first_map * 4 + i;
        k.scan_index = first_map * 4 + i;
        k.local_map_id = first_map + i / 4;
        k.stamp = t0 + double(i);
        k.T_odom_lidar = odom[i];
        k.T_anchor_lidar = maps[i / 4].T_odom_anchor.inverse() * odom[i];
        k.points = points[i];
        return k;
    }
};

inline MapperConfig test_config() {
    MapperConfig c;
    c.loop_detection.exclude_recent_keyframes = 6;
    c.loop_detection.exclude_recent_seconds = 0.0;
    c.loop_detection.max_distance = 0.6;
    c.loop_detection.max_results = 1;
    c.loop_cooldown_keyframes = 1;
    return c;
}

// Keyframes, each local map finished after its last one; optimised when a loop makes it due.
inline std::vector<KeyframeResult> replay(const Drive& d, Mapper& mapper,
                                          std::vector<LocalMapResult>* maps = nullptr) {
    std::vector<KeyframeResult> out;
    for (std::size_t i = 0; i < 16; ++i) {
        out.push_back(mapper.add_keyframe(d.keyframe(i)));
        EXPECT_TRUE(out.back().added) << out.back().message;
        if (out.back().optimisation_due()) {
            EXPECT_TRUE(mapper.optimise().solved);
        }
        if (i % 4 == 3) {
            const LocalMapResult r = mapper.add_local_map(d.maps[i / 4]);
            EXPECT_TRUE(r.added) << r.message;
            if (maps) maps->push_back(r);
        }
    }
    return out;
}
}  // namespace ltm::mapping::test
