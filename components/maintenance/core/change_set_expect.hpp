#pragma once
// Test helper: two change sets equal field by field (gtest expectations naming the field).
#include <gtest/gtest.h>

#include "maintenance/core/change_set.hpp"

namespace ltm::maintenance {

inline void expect_same_changes(const ChangeSet& a, const ChangeSet& b) {
    EXPECT_EQ(a.session, b.session);
    EXPECT_EQ(a.map_time, b.map_time);
    EXPECT_EQ(a.voxel_size, b.voxel_size);
    EXPECT_EQ(a.voxels_before, b.voxels_before);
    EXPECT_EQ(a.voxels_removed, b.voxels_removed);
    EXPECT_EQ(a.voxels_judged, b.voxels_judged);
    EXPECT_EQ(a.segments, b.segments);
    EXPECT_EQ(a.ground_voxels, b.ground_voxels);
    EXPECT_EQ(a.time_ms, b.time_ms);
    ASSERT_EQ(a.changes.size(), b.changes.size());
    for (std::size_t i = 0; i < a.changes.size(); ++i) {
        const SegmentChange &x = a.changes[i], &y = b.changes[i];
        EXPECT_EQ(x.id, y.id);
        EXPECT_EQ(x.reason, y.reason);
        EXPECT_EQ(x.region, y.region);
        EXPECT_EQ(x.centroid, y.centroid);
        EXPECT_EQ(x.bbox_min, y.bbox_min);
        EXPECT_EQ(x.bbox_max, y.bbox_max);
        EXPECT_EQ(x.first_seen, y.first_seen);
        EXPECT_EQ(x.last_seen, y.last_seen);
        EXPECT_EQ(x.score, y.score);
        EXPECT_EQ(x.judged, y.judged);
        EXPECT_EQ(x.voxels, y.voxels);
    }
}

}  // namespace ltm::maintenance
