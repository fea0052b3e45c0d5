#include "evaluation/core/object_account.hpp"

#include <gtest/gtest.h>

namespace ltm::eval {
namespace {

SiteObject car(std::uint32_t id, double x, double y) {
    SiteObject o;
    o.id = id;
    o.kind = "car";
    o.x = x, o.y = y;
    o.length = 4.0, o.width = 2.0, o.height = 1.5;
    return o;
}

// Voxel centres every 0.5 m over an object's box (x from -1.75 to 1.75: 8 x 4 x 3 = 96).
void fill(const SiteObject& o, std::vector<Eigen::Vector3d>& out) {
    for (double a = -1.75; a <= 1.75; a += 0.5)
        for (double b = -0.75; b <= 0.75; b += 0.5)
            for (double z = 0.5; z <= 1.5; z += 0.5) out.emplace_back(o.x + a, o.y + b, z);
}

TEST(ObjectAccount, SplitsTodayFromEarlierAndLeavesOutStandingNeighbours) {
    // Day 0: cars 1 and 2 side by side (0.2 m apart, within the 0.3 m margin), car 3 elsewhere.
    const SiteObject a = car(1, 0, 0), b = car(2, 4.2, 0), c = car(3, 30, 0);
    std::vector<Eigen::Vector3d> first;
    fill(a, first);
    fill(b, first);
    fill(c, first);
    // Car 1 left today (it stood there yesterday); car 3 left yesterday already; car 2 stays.
    const std::vector<SiteObject> yesterday = {a, b};
    const std::vector<SiteObject> today = {b};
    ObjectChanges changes;
    changes.removed = {a, c};
    // The map the day started from still had car 1 and (wrongly) car 3; after it: a quarter of
    // car 1's voxels and car 2 (whose end reaches into car 1's grown box).
    std::vector<Eigen::Vector3d> start = first, later;
    std::vector<Eigen::Vector3d> a_voxels;
    fill(a, a_voxels);
    later.insert(later.end(), a_voxels.begin(), a_voxels.begin() + 24);
    fill(b, later);
    const std::vector<Eigen::Vector3d> route = {{0, 10, 0}, {10, 10, 0}};

    const std::vector<ObjectAccount> acc =
        account_left_places(first, start, later, changes, yesterday, today, route);
    ASSERT_EQ(acc.size(), 2u);
    EXPECT_EQ(acc[0].object.id, 1u);
    EXPECT_TRUE(acc[0].today);
    EXPECT_DOUBLE_EQ(acc[0].route_distance, 10.0);
    // Car 2's voxels in car 1's grown box are car 2's: not counted, before or after.
    EXPECT_EQ(acc[0].before, 96u);
    EXPECT_EQ(acc[0].at_start, 96u);
    EXPECT_EQ(acc[0].kept, 24u);
    EXPECT_EQ(acc[1].object.id, 3u);
    EXPECT_FALSE(acc[1].today);
    EXPECT_EQ(acc[1].before, 96u);
    EXPECT_EQ(acc[1].at_start, 96u);
    EXPECT_EQ(acc[1].kept, 0u);

    const AccountTotals t = sum_accounts(acc, "removed", true);
    EXPECT_EQ(t.objects, 1u);
    EXPECT_EQ(t.before, 96u);
    EXPECT_EQ(t.kept, 24u);
    EXPECT_EQ(sum_accounts(acc, "removed", false).kept, 0u);
    EXPECT_EQ(sum_accounts(acc, "moved", true).objects, 0u);
}

TEST(ObjectAccount, AMovedObjectLeftTodayOnlyWhenItStoodAtItsFirstPlaceYesterday) {
    const SiteObject first_place = car(5, 0, 0);
    SiteObject moved = first_place;
    moved.x = 20;
    ObjectChanges changes;
    changes.moved_from = {first_place};
    changes.moved_to = {moved};
    std::vector<Eigen::Vector3d> map;
    fill(first_place, map);
    const std::vector<Eigen::Vector3d> route = {{0, 0, 0}};
    EXPECT_TRUE(account_left_places(map, map, {}, changes, {first_place}, {moved}, route)[0].today);
    EXPECT_FALSE(account_left_places(map, map, {}, changes, {moved}, {moved}, route)[0].today);
    EXPECT_FALSE(account_left_places(map, map, {}, changes, {}, {moved}, route)[0].today);
}

}  // namespace
}  // namespace ltm::eval
