// LocalMapData -> ltm_msgs/LocalMap (LocalMapBuilder) -> LocalMapData (from_msg), in memory: every
// field comes back, the odometry segment included.
#include "runtime/convert/local_map.hpp"

#include <gtest/gtest.h>

using namespace ltm;

namespace {

Eigen::Isometry3d some_pose(double k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() =
        Eigen::AngleAxisd(0.3 * k, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(k, -2 * k, 0.5 * k);
    return T;
}

common::LocalMapData some_map(std::uint32_t segment) {
    common::LocalMapData d;
    d.id = 17;
    d.revision = 4;
    d.finished = false;
    d.segment = segment;
    d.T_odom_anchor = some_pose(1.5);
    d.T_anchor_grid = some_pose(-0.5);
    d.bbox_min = {-40, -30, -5};
    d.bbox_max = {40, 30, 8};
    d.voxel_size = 0.5f;
    d.observation_times = {7.0, 7.1, 7.25};
    for (int i = 0; i < 5; ++i) {
        common::VoxelData v;
        v.index = {i, -i, 2 * i};
        v.centre = {0.1f * i, 0.2f, -0.3f};
        v.normal = {0, 1, 0};
        v.point_count = 3u + std::uint32_t(i);
        v.planarity = 0.7f;
        v.stability = 0.9f;
        v.life = {7.0, 7.25, 3, 0.75f, {0, 2}};
        d.voxels.push_back(v);
    }
    return d;
}

TEST(LocalMapConversion, EveryFieldComesBackWithTheSegment) {
    for (const std::uint32_t segment : {0u, 3u, 4000000000u}) {
        const common::LocalMapData d = some_map(segment);
        convert::LocalMapBuilder builder;
        const msg::LocalMap& m = builder.build(d, 7.25, "odom");
        EXPECT_EQ(m.segment, segment);
        EXPECT_STREQ(m.header.frame_id, "odom");
        const common::LocalMapData r = convert::from_msg(m);
        EXPECT_EQ(r.segment, segment);
        EXPECT_EQ(r.id, d.id);
        EXPECT_EQ(r.revision, d.revision);
        EXPECT_EQ(r.finished, d.finished);
        EXPECT_TRUE(r.T_odom_anchor.isApprox(d.T_odom_anchor, 1e-12));
        EXPECT_TRUE(r.T_anchor_grid.isApprox(d.T_anchor_grid, 1e-12));
        EXPECT_EQ(r.bbox_min, d.bbox_min);
        EXPECT_EQ(r.bbox_max, d.bbox_max);
        EXPECT_EQ(r.voxel_size, d.voxel_size);
        EXPECT_EQ(r.observation_times, d.observation_times);
        ASSERT_EQ(r.voxels.size(), d.voxels.size());
        for (std::size_t i = 0; i < d.voxels.size(); ++i) {
            EXPECT_EQ(r.voxels[i].index, d.voxels[i].index);
            EXPECT_EQ(r.voxels[i].centre, d.voxels[i].centre);
            EXPECT_EQ(r.voxels[i].normal, d.voxels[i].normal);
            EXPECT_EQ(r.voxels[i].point_count, d.voxels[i].point_count);
            EXPECT_EQ(r.voxels[i].planarity, d.voxels[i].planarity);
            EXPECT_EQ(r.voxels[i].stability, d.voxels[i].stability);
            EXPECT_EQ(r.voxels[i].life.created, d.voxels[i].life.created);
            EXPECT_EQ(r.voxels[i].life.last_seen, d.voxels[i].life.last_seen);
            EXPECT_EQ(r.voxels[i].life.observations, d.voxels[i].life.observations);
            EXPECT_EQ(r.voxels[i].life.health, d.voxels[i].life.health);
            EXPECT_EQ(r.voxels[i].life.seen, d.voxels[i].life.seen);
        }
    }
}

}  // namespace
