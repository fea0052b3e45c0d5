// ChangeSet <-> ltm_msgs/MapChangeSet: exact through the converter and through Cyclone DDS
// (serialised, delivered, deserialised); malformed messages refused with one line.
#include "maintenance/component/map_change_messages.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "maintenance/core/change_set_expect.hpp"
#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"
#include "runtime/testing/dds_loopback.hpp"

namespace ltm::maintenance {
namespace {

ChangeSet sample() {
    ChangeSet c;
    c.session = 2;
    c.map_time = 301.25;
    c.voxel_size = 0.25f;
    c.voxels_before = 12345;
    c.voxels_removed = 3;
    c.voxels_judged = 999;
    c.segments = 17;
    c.ground_voxels = 8000;
    c.time_ms = 4.75;
    const ChangeReason reasons[] = {ChangeReason::kMoving, ChangeReason::kVanished,
                                    ChangeReason::kNew};
    for (int i = 0; i < 3; ++i) {
        SegmentChange s;
        s.id = 100 + i;
        s.reason = reasons[i];
        s.region = {i - 1, 2 * i};
        s.voxels = {{0.1f * i, -1.3f, 0.7f}, {0.35f, 2.0f + i, -0.2f}};
        s.centroid = (s.voxels[0] + s.voxels[1]) / 2;
        s.bbox_min = s.voxels[0].cwiseMin(s.voxels[1]);
        s.bbox_max = s.voxels[0].cwiseMax(s.voxels[1]);
        s.first_seen = 10.0 * i;
        s.last_seen = 10.0 * i + 2.5;
        s.score = 0.3 + 0.1 * i;
        s.judged = i;
        c.changes.push_back(s);
    }
    c.changes.back().voxels.push_back({7.0f, 8.0f, 9.0f});
    return c;
}

TEST(MapChangeMessages, RoundTripThroughTheConverterIsExact) {
    const ChangeSet c = sample();
    const convert::Owned<msg::MapChangeSet> m = to_msg(c, 5, 1700000000.5, "map");
    EXPECT_EQ(m->pass, 5u);
    EXPECT_EQ(convert::to_string(m->header.frame_id), "map");
    EXPECT_DOUBLE_EQ(convert::to_seconds(m->header.stamp), 1700000000.5);
    ASSERT_EQ(m->changes._length, 3u);
    EXPECT_EQ(m->changes._buffer[1].reason, ltm_msgs_msg_SegmentChange_Constants_VANISHED);
    EXPECT_EQ(m->changes._buffer[2].voxels._length, 9u);
    expect_same_changes(c, from_msg(*m));
    expect_same_changes(ChangeSet{}, from_msg(*to_msg(ChangeSet{}, 0, 0.0, "map")));
}

TEST(MapChangeMessages, MalformedMessagesAreRefusedInOneLine) {
    convert::Owned<msg::MapChangeSet> m = to_msg(sample(), 0, 1.0, "map");
    m->changes._buffer[1].reason = 7;
    try {
        from_msg(*m);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "map change set: changes[1]: unknown reason 7");
    }
    m->changes._buffer[1].reason = ltm_msgs_msg_SegmentChange_Constants_NEW;
    m->changes._buffer[2].voxels._length = 8;
    try {
        from_msg(*m);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(),
                     "map change set: changes[2]: 8 voxel coordinates, not x y z triples");
    }
    m->changes._buffer[2].voxels._length = 9;
}

// Serialised by Cyclone DDS and taken back by a reader of the same topic.
TEST(MapChangeMessages, RoundTripThroughDds) {
    const ChangeSet c = sample();
    runtime::testing::DdsLoopback dds(221);
    dds.roundtrip<msg::MapChangeSet>(*to_msg(c, 3, 42.0, "map"), [&](const msg::MapChangeSet& r) {
        EXPECT_EQ(r.pass, 3u);
        expect_same_changes(c, from_msg(r));
    });
}

}  // namespace
}  // namespace ltm::maintenance
