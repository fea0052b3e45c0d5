#include "odometry/core/map_handover.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "registration/core/test_scenes.hpp"

namespace ltm::odometry {
namespace {

Eigen::Isometry3d street_pose(int i) {
    return registration::test::make_pose(1.0 * i, 0.4 * std::sin(i / 5.0), 1.8, 0.0, 0.0,
                                         3.0 * std::sin(i / 8.0));
}

// 36 scans along the synthetic street; every handover checked against the odometry's own state.
TEST(MapHandover, HandsOverKeyframesFinishedMapsAndSnapshotsWithObservationTimes) {
    const registration::test::Scene scene = registration::test::street_scene();
    OdometryConfig config;
    config.local_map.half_extent = 40.0;
    config.local_map.switch_distance = 12.0;
    config.keyframe.distance = 2.0;
    Odometry odo(config, street_pose(0));
    HandoverConfig hc;
    hc.snapshot_every_keyframes = 3;
    MapHandover handover(hc);
    std::map<std::uint64_t, std::vector<double>> stamps_in;  // map -> stamps it was active for
    std::map<std::uint64_t, int> finished_count;
    std::uint32_t last_revision = 0;
    std::size_t keyframes = 0, snapshots = 0;
    auto check_map = [&](const common::LocalMapData& m) {
        EXPECT_GT(m.revision, last_revision) << "revisions count every handed-over map";
        last_revision = m.revision;
        EXPECT_FALSE(m.voxels.empty());
        EXPECT_EQ(m.observation_times, stamps_in[m.id]) << "map " << m.id;
        if (m.finished) {
            ++finished_count[m.id];
        } else {
            ++snapshots;
        }
    };
    const int frames = 36;
    for (int i = 0; i < frames; ++i) {
        registration::test::ScanPattern pattern;
        common::PointCloud c =
            registration::test::scan_scene(scene, pattern, street_pose(i), street_pose(i), 100 + i);
        c.stamp = 0.1 * i;
        const FrameResult r = odo.register_frame(c);
        ASSERT_TRUE(r.pose_valid()) << i << ": " << r.message;
        for (const LocalMap& m : odo.active_local_maps()) stamps_in[m.id()].push_back(c.stamp);
        // (A map retired by this scan left the active set before the scan was integrated.)
        const Handover h = handover.after_frame(odo, r, std::uint64_t(i));
        EXPECT_EQ(h.keyframe.has_value(), r.keyframe.has_value());
        if (h.keyframe) {
            ++keyframes;
            EXPECT_EQ(h.keyframe->scan_index, std::uint64_t(i));
            EXPECT_EQ(h.keyframe->local_map_id, r.keyframe->local_map_id);
            EXPECT_TRUE(h.keyframe->T_odom_lidar.isApprox(r.T_odom_lidar, 1e-12));
            bool anchored = false;
            for (const LocalMap& m : odo.active_local_maps()) {
                if (m.id() != h.keyframe->local_map_id) continue;
                anchored =
                    (m.T_odom_anchor() * h.keyframe->T_anchor_lidar).isApprox(r.T_odom_lidar, 1e-9);
            }
            EXPECT_TRUE(anchored) << "keyframe " << i;
        }
        bool snapshot_seen = false;
        for (const common::LocalMapData& m : h.local_maps) {
            if (m.finished) {
                EXPECT_FALSE(snapshot_seen) << "finished maps come before snapshots";
            } else {
                snapshot_seen = true;
            }
            check_map(m);
        }
        EXPECT_EQ(snapshot_seen, h.keyframe && keyframes % 3 == 0) << "scan " << i;
    }
    for (const common::LocalMapData& m : handover.finish(odo)) {
        EXPECT_TRUE(m.finished);
        check_map(m);
    }
    EXPECT_GE(keyframes, 10u);
    EXPECT_GE(snapshots, 3u);
    EXPECT_GE(finished_count.size(), 3u) << "the street spans several local maps";
    for (const auto& [id, n] : finished_count) EXPECT_EQ(n, 1) << "map " << id << " finished once";
    EXPECT_EQ(finished_count.size(), stamps_in.size()) << "every map was handed over finished";
    EXPECT_EQ(handover.keyframes(), keyframes);
}

}  // namespace
}  // namespace ltm::odometry
