#include "evaluation/core/map_change_score.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace ltm::eval {
namespace {

SiteObject box(std::uint32_t id, double x, double y) {
    SiteObject o;
    o.id = id;
    o.kind = "car";
    o.x = x, o.y = y;
    o.length = 4.0, o.width = 2.0, o.height = 1.5;
    return o;
}

// Voxel centres every 0.5 m over an object's box.
void fill(const SiteObject& o, std::vector<Eigen::Vector3d>& out) {
    for (double a = -1.75; a <= 1.75; a += 0.5)
        for (double b = -0.75; b <= 0.75; b += 0.5)
            for (double z = 0.5; z <= 1.5; z += 0.5) out.emplace_back(o.x + a, o.y + b, z);
}

TEST(MapChangeScore, CountsWhatTheLaterMapKept) {
    const SiteObject gone = box(1, 0, 0), moved_old = box(2, 20, 0), moved_new = box(2, 20, 10),
                     added = box(3, 40, 0), stays = box(4, 60, 0);
    std::vector<Eigen::Vector3d> ground;  // a static patch far from every object
    for (double x = 80; x < 90; x += 0.5)
        for (double y = 0; y < 10; y += 0.5) ground.emplace_back(x, y, 0.0);

    std::vector<Eigen::Vector3d> first = ground;
    fill(gone, first);       // 8 x 4 x 3 = 96 voxels
    fill(moved_old, first);  // 96
    fill(stays, first);      // 96, an object that changes on another day
    // The later map: half of the removed object still there, the moved one's old place empty,
    // its new place and the added object in, a tenth of the ground lost.
    std::vector<Eigen::Vector3d> later;
    for (std::size_t i = 0; i < ground.size(); ++i)
        if (i % 10 != 0) later.push_back(ground[i]);
    std::vector<Eigen::Vector3d> gone_voxels;
    fill(gone, gone_voxels);
    later.insert(later.end(), gone_voxels.begin(), gone_voxels.begin() + 48);
    fill(moved_new, later);
    fill(added, later);
    fill(stays, later);

    // The ground under the added object is in both maps: it is no voxel of the object.
    std::vector<Eigen::Vector3d> under_added;
    for (double a = -1.5; a <= 1.5; a += 0.5) under_added.emplace_back(40 + a, 0.0, 0.1);
    first.insert(first.end(), under_added.begin(), under_added.end());
    later.insert(later.end(), under_added.begin(), under_added.end());

    ObjectChanges changes;
    changes.removed = {gone};
    changes.moved_from = {moved_old};
    changes.moved_to = {moved_new};
    changes.added = {added};
    const MapChangeScore s = score_map_changes(first, later, changes, {stays});
    EXPECT_EQ(s.removed_before, 96u);
    EXPECT_EQ(s.removed_kept, 48u);
    EXPECT_EQ(s.moved_from_before, 96u);
    EXPECT_EQ(s.moved_from_kept, 0u);
    EXPECT_EQ(s.moved_objects, 1u);
    EXPECT_EQ(s.moved_to_present, 1u);
    EXPECT_EQ(s.moved_to_voxels, 96u);
    EXPECT_EQ(s.added_objects, 1u);
    EXPECT_EQ(s.added_present, 1u);
    EXPECT_EQ(s.added_voxels, 96u);
    // Static: the ground only (the unstable object is excluded). Its lost voxels have a
    // neighbour 0.5 m away in the later map, so only a radius below that sees them as lost.
    EXPECT_EQ(s.static_before, ground.size());
    EXPECT_EQ(s.static_kept, ground.size());
    MapChangeConfig strict;
    strict.static_radius = 0.2;
    const MapChangeScore t = score_map_changes(first, later, changes, {stays}, strict);
    EXPECT_EQ(t.static_kept, ground.size() - (ground.size() + 9) / 10);
    EXPECT_TRUE(s.static_lost.empty());
    ASSERT_EQ(t.static_lost.size(), t.static_before - t.static_kept);
    for (const auto& p : t.static_lost)  // each one a first-map voxel the later map has not
        EXPECT_TRUE(std::find(later.begin(), later.end(), p) == later.end()) << p.transpose();
}

TEST(MapChangeScore, EmptyMapsScoreZero) {
    ObjectChanges changes;
    changes.added = {box(3, 40, 0)};
    const MapChangeScore s = score_map_changes({}, {}, changes, {});
    EXPECT_EQ(s.added_objects, 1u);
    EXPECT_EQ(s.added_present, 0u);
    EXPECT_EQ(s.static_before, 0u);
    // Ground alone in an added object's box does not make it present.
    const std::vector<Eigen::Vector3d> ground{{39, 0, 0.0}, {40, 0, 0.1}, {41, 0, 0.2}};
    EXPECT_EQ(score_map_changes(ground, ground, changes, {}).added_present, 0u);
}

// A fence on a slope is sunk to its lowest ground (base_z) and stands on higher ground at its
// other end: the ground there, under a fence removed, is no voxel of the fence (the ten days of
// repeat_fortnight counted 8-11 ground voxels a day as a removed fence's, issue 26).
TEST(MapChangeScore, TheGroundAtASunkFencesHighEndIsNoVoxelOfTheFence) {
    SiteObject fence;
    fence.id = 1;
    fence.kind = "fence";
    fence.x = 8.0, fence.y = 0.0, fence.base_z = -0.3;
    fence.length = 16.0, fence.width = 0.1, fence.height = 2.4;
    fence.ground_z = {-0.3, -0.15, 0.0, 0.15, 0.3};  // west end to east end
    std::vector<Eigen::Vector3d> first, later;
    for (double x = 0.25; x < 16.0; x += 0.5) {
        const double ground = -0.3 + 0.6 * x / 16.0;
        first.emplace_back(x, 0.0, ground);  // the ground along the fence (and under it)
        later.emplace_back(x, 0.0, ground);  // the fence gone, its ground stays
        // The fence up to its top, base_z + height all along (the ground hides its foot).
        for (double z = ground + 0.5; z < 2.1; z += 0.5) first.emplace_back(x, 0.0, z);
    }
    ObjectChanges changes;
    changes.removed = {fence};
    const MapChangeScore s = score_map_changes(first, later, changes, {});
    EXPECT_EQ(s.removed_kept, 0u);  // with base_z alone: the east half's ground, 0.3 m up and more
    EXPECT_EQ(s.removed_before, first.size() - later.size());
    SiteObject flat = fence;
    flat.ground_z.clear();  // without the ground: base_z all along (as before)
    changes.removed = {flat};
    EXPECT_GT(score_map_changes(first, later, changes, {}).removed_kept, 5u);
}

}  // namespace
}  // namespace ltm::eval
