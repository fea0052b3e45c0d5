#include "mapping/core/local_map_merge.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "mapping/core/mapper_config.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

struct CellLess {
    bool operator()(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const {
        return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    }
};

std::map<Eigen::Vector3i, const common::VoxelData*, CellLess> by_cell(
    const common::LocalMapData& m) {
    std::map<Eigen::Vector3i, const common::VoxelData*, CellLess> out;
    for (const common::VoxelData& v : m.voxels) out[v.index] = &v;
    return out;
}

common::VoxelData voxel(const Eigen::Vector3i& index, const Eigen::Vector3f& centre,
                        const Eigen::Vector3f& normal, std::uint32_t points) {
    common::VoxelData v;
    v.index = index;
    v.centre = centre;
    v.normal = normal;
    v.point_count = points;
    v.planarity = 0.5f;
    v.stability = 1.0f;
    return v;
}

// A map built from a scene, and the same scene seen from 7 m further on and turned by 30 deg:
// the second map's anchor is T_shift in the first's. Merged, the second adds no voxel where the
// first already has one (the same surfaces land in the same cells), and every voxel of the second
// is found in the merged map where the first's frame puts it.
TEST(LocalMapMerge, AMapMergedWithItselfShiftedByAKnownTransformLandsOnItsOwnCells) {
    const std::vector<Eigen::Vector3f> scene =
        registration::test::with_dense_ground(registration::test::synthetic_scene(5));
    const Eigen::Isometry3d at_a = registration::test::xy_yaw(0, 0, 0);
    const common::LocalMapData a = registration::test::build_local_map(
        0, at_a, {registration::test::view(scene, at_a, 30.0)}, {at_a}, 1.0, 30.0);
    // The second map: the same view in another odometry frame, anchored 7 m on and turned.
    const Eigen::Isometry3d T_shift = registration::test::xy_yaw(7.0, -2.0, 30.0);
    const Eigen::Isometry3d T_odom2_world = registration::test::xy_yaw(-40.0, 12.0, -70.0);
    const common::LocalMapData b = registration::test::build_local_map(
        1, T_odom2_world * T_shift, {registration::test::view(scene, at_a, 30.0)},
        {T_odom2_world * at_a}, 1.0, 30.0);
    const common::LocalMapData m = merge_local_maps(a, b, T_shift, 1024);

    EXPECT_EQ(m.id, a.id);
    EXPECT_EQ(m.revision, a.revision + 1);
    EXPECT_TRUE(m.T_odom_anchor.isApprox(a.T_odom_anchor));
    // Not every voxel lands on the identical cell (the second lattice is turned, so the means
    // differ a little), but nearly all do, and the merged map is far smaller than the two.
    EXPECT_LT(m.voxels.size(), a.voxels.size() + b.voxels.size() / 4);
    std::uint64_t pa = 0, pb = 0, pm = 0;
    for (const auto& v : a.voxels) pa += v.point_count;
    for (const auto& v : b.voxels) pb += v.point_count;
    for (const auto& v : m.voxels) pm += v.point_count;
    EXPECT_EQ(pm, pa + pb);  // every point counted once
    // Each voxel of b, through T_shift and a's grid, is in a cell of the merged map.
    const auto cells = by_cell(m);
    const Eigen::Isometry3d T = a.T_anchor_grid.inverse() * T_shift * b.T_anchor_grid;
    for (const common::VoxelData& v : b.voxels) {
        const Eigen::Vector3d p = T * v.centre.cast<double>();
        const Eigen::Vector3i c(int(std::floor(p.x())), int(std::floor(p.y())),
                                int(std::floor(p.z())));
        ASSERT_TRUE(cells.count(c)) << p.transpose();
        const common::VoxelData& w = *cells.at(c);
        EXPECT_TRUE(((w.centre.cast<double>() - c.cast<double>()).array() >= -1e-4).all());
        EXPECT_TRUE(((w.centre.cast<double>() - c.cast<double>()).array() <= 1.0 + 1e-4).all());
        if (w.normal.squaredNorm() > 0.0f) {
            EXPECT_NEAR(w.normal.norm(), 1.0f, 1e-4f);
        }
    }
    // The box covers both.
    EXPECT_LE(m.bbox_min.x(), a.bbox_min.x());
    EXPECT_GE(m.bbox_max.x(), a.bbox_max.x() + 5.0);
}

TEST(LocalMapMerge, VoxelsInOneCellMergeTheirCentreNormalAndLife) {
    common::LocalMapData a, b;
    a.voxel_size = b.voxel_size = 1.0f;
    a.observation_times = {1.0, 2.0, 3.0};
    b.observation_times = {10.0, 11.0};
    common::VoxelData va = voxel({0, 0, 0}, {0.2f, 0.5f, 0.5f}, {0, 0, 1}, 3);
    va.life = {1.0, 3.0, 3, 1.0f, {0, 1, 2}};
    common::VoxelData vb = voxel({0, 0, 0}, {0.8f, 0.5f, 0.5f}, {0, 0, -1}, 1);  // flipped normal
    vb.life = {10.0, 11.0, 2, 0.0f, {0, 1}};
    a.voxels = {va};
    b.voxels = {vb};
    const common::LocalMapData m = merge_local_maps(a, b, Eigen::Isometry3d::Identity(), 1024);
    ASSERT_EQ(m.voxels.size(), 1u);
    const common::VoxelData& v = m.voxels[0];
    EXPECT_NEAR(v.centre.x(), (3 * 0.2f + 0.8f) / 4, 1e-6f);
    EXPECT_NEAR(v.normal.z(), 1.0f, 1e-6f);  // sign-aligned: not cancelled
    EXPECT_EQ(v.point_count, 4u);
    EXPECT_EQ(v.life.created, 1.0);
    EXPECT_EQ(v.life.last_seen, 11.0);
    EXPECT_EQ(v.life.observations, 5u);
    EXPECT_NEAR(v.life.health, 0.6f, 1e-6f);  // observation-weighted
    EXPECT_EQ(m.observation_times, (std::vector<double>{1, 2, 3, 10, 11}));
    EXPECT_EQ(v.life.seen, (std::vector<std::uint16_t>{0, 1, 2, 3, 4}));

    // A voxel of b in a cell a does not have keeps its own record, its seen indices remapped.
    b.voxels[0].index = {2, 0, 0};
    b.voxels[0].centre = {2.5f, 0.5f, 0.5f};
    const common::LocalMapData m2 = merge_local_maps(a, b, Eigen::Isometry3d::Identity(), 1024);
    ASSERT_EQ(m2.voxels.size(), 2u);
    EXPECT_EQ(m2.voxels[1].life.seen, (std::vector<std::uint16_t>{3, 4}));
    EXPECT_EQ(m2.voxels[1].life.created, 10.0);
}

TEST(LocalMapMerge, ObservationTimesStayBoundedKeepingTheRecentOnesAndAnEvenSampleOfTheOld) {
    std::vector<double> times;
    for (int i = 0; i < 100; ++i) times.push_back(double(i));
    std::vector<double> kept;
    const std::vector<std::uint32_t> index = bound_observation_times(times, 10, &kept);
    ASSERT_EQ(kept.size(), 10u);
    // The newest five all kept; five of the 95 older ones, first and last among them.
    EXPECT_EQ(kept, (std::vector<double>{0, 24, 47, 71, 94, 95, 96, 97, 98, 99}));
    EXPECT_EQ(index[0], 0u);
    EXPECT_EQ(index[99], 9u);
    EXPECT_EQ(index[30], 1u);  // 30 is nearest to 24
    EXPECT_EQ(index[40], 2u);  // 40 is nearest to 47
    // Below the bound nothing changes.
    const std::vector<std::uint32_t> same = bound_observation_times({1, 2, 3}, 10, &kept);
    EXPECT_EQ(kept, (std::vector<double>{1, 2, 3}));
    EXPECT_EQ(same, (std::vector<std::uint32_t>{0, 1, 2}));

    // Merging maps again and again: the times stay within the bound, the seen indices valid and
    // the newest map's stamps all there.
    common::LocalMapData m;
    m.voxel_size = 1.0f;
    for (int round = 0; round < 12; ++round) {
        common::LocalMapData next;
        next.voxel_size = 1.0f;
        common::VoxelData v = voxel({0, 0, 0}, {0.5f, 0.5f, 0.5f}, {0, 0, 1}, 1);
        for (int k = 0; k < 20; ++k) {
            next.observation_times.push_back(100.0 * round + k);
            v.life.seen.push_back(std::uint16_t(k));
        }
        v.life.created = 100.0 * round;
        v.life.last_seen = 100.0 * round + 19;
        next.voxels = {v};
        m = merge_local_maps(m, next, Eigen::Isometry3d::Identity(), 64);
        ASSERT_LE(m.observation_times.size(), 64u);
        ASSERT_TRUE(std::is_sorted(m.observation_times.begin(), m.observation_times.end()));
        for (const std::uint16_t s : m.voxels[0].life.seen)
            ASSERT_LT(s, m.observation_times.size());
    }
    EXPECT_EQ(m.observation_times.size(), 64u);
    EXPECT_EQ(m.observation_times.back(), 1119.0);
    EXPECT_EQ(m.observation_times.front(), 0.0);  // the oldest stays as the record's start
    EXPECT_EQ(m.voxels[0].life.seen.size(), 64u);
}

// Another day sees the same ground 3 cm higher (its pose), just across the cells' top faces: with
// same_surface the existing voxels take those observations (no voxel added, every point counted,
// the centres on the old plane and in their own cells); ground beyond the old patch still adds
// voxels. Without it the map doubles (issue 26: a place driven again grew every day).
TEST(LocalMapMerge, ASurfaceSeenAgainAcrossACellFaceUpdatesTheVoxelsThereInsteadOfAddingSome) {
    common::LocalMapData a, b;
    a.voxel_size = b.voxel_size = 1.0f;
    a.observation_times = {1.0};
    b.observation_times = {86401.0};
    for (int x = 0; x < 5; ++x) {
        for (int y = 0; y < 5; ++y) {
            common::VoxelData va = voxel({x, y, 0}, {x + 0.5f, y + 0.5f, 0.98f}, {0, 0, 1}, 10);
            va.life = {1.0, 1.0, 1, 1.0f, {}};
            a.voxels.push_back(va);
        }
    }
    // b: the same patch, and two more rows east of it (x = 5, 6), all at z = 1.01.
    for (int x = 0; x < 7; ++x) {
        for (int y = 0; y < 5; ++y) {
            common::VoxelData vb = voxel({x, y, 1}, {x + 0.5f, y + 0.5f, 1.01f}, {0, 0, -1}, 6);
            vb.life = {86401.0, 86401.0, 1, 1.0f, {}};
            b.voxels.push_back(vb);
        }
    }
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    EXPECT_EQ(merge_local_maps(a, b, I, 1024).voxels.size(), 60u);  // without: 25 + 35

    std::size_t absorbed = 0;
    const common::LocalMapData m = merge_local_maps(a, b, I, 1024, 0.2, &absorbed);
    EXPECT_EQ(absorbed, 25u);
    ASSERT_EQ(m.voxels.size(), 35u);  // the old patch, and the ground beyond it
    std::uint64_t points = 0;
    for (const common::VoxelData& v : m.voxels) {
        points += v.point_count;
        const Eigen::Vector3f lo = v.index.cast<float>();
        EXPECT_TRUE(((v.centre - lo).array() >= 0.0f).all()) << v.index.transpose();
        EXPECT_TRUE(((v.centre - lo).array() <= 1.0f).all()) << v.index.transpose();
        if (v.index.z() == 0) {
            EXPECT_LT(v.index.x(), 5);
            EXPECT_NEAR(v.centre.z(), 0.98f, 1e-5f);  // on the old plane
            EXPECT_EQ(v.point_count, 16u);
            EXPECT_EQ(v.life.observations, 2u);
            EXPECT_EQ(v.life.last_seen, 86401.0);
        } else {
            EXPECT_GE(v.index.x(), 5);  // beyond the patch: its own voxel
            EXPECT_EQ(v.life.created, 86401.0);
        }
    }
    EXPECT_EQ(points, 25u * 10u + 35u * 6u);

    // Not the same surface: a wall (normal along x) 0.3 m above the ground's cells stays its own.
    common::LocalMapData wall;
    wall.voxel_size = 1.0f;
    wall.observation_times = {86401.0};
    wall.voxels = {voxel({2, 2, 1}, {2.5f, 2.5f, 1.3f}, {1, 0, 0}, 6)};
    EXPECT_EQ(merge_local_maps(a, wall, I, 1024, 0.2).voxels.size(), 26u);
    wall.voxels = {voxel({2, 2, 1}, {2.5f, 2.5f, 1.3f}, {0, 0, 1}, 6)};  // 0.32 m above the plane
    EXPECT_EQ(merge_local_maps(a, wall, I, 1024, 0.2).voxels.size(), 26u);
}

// Another day's view shows the old ground one cell beyond its patch (a ring of cells around it, on
// its plane but the foot outside every old cell): with beside_surface those voxels add nothing,
// while ground two cells on, a box standing on the old ground (its top 1 m over the ground's plane,
// its sides upright) and a wall beside the ground enter as before, and so does a hole in the patch.
TEST(LocalMapMerge, TheOldSurfaceOneCellBeyondItsPatchAddsNothingNewSurfacesStillEnter) {
    common::LocalMapData a, b;
    a.voxel_size = b.voxel_size = 1.0f;
    a.observation_times = {1.0};
    b.observation_times = {86401.0};
    for (int x = 0; x < 5; ++x)
        for (int y = 0; y < 5; ++y)
            a.voxels.push_back(voxel({x, y, 0}, {x + 0.5f, y + 0.5f, 0.5f}, {0, 0, 1}, 10));
    // The ring around the patch (x or y = -1 or 5) on the ground's plane, 5 cm higher.
    int ring = 0;
    for (int x = -1; x <= 5; ++x)
        for (int y = -1; y <= 5; ++y)
            if (x < 0 || x > 4 || y < 0 || y > 4) {
                b.voxels.push_back(voxel({x, y, 0}, {x + 0.5f, y + 0.5f, 0.55f}, {0, 0, 1}, 6));
                ++ring;
            }
    // Ground two cells beyond the patch (x = 6): not beside an old voxel.
    for (int y = 0; y < 5; ++y)
        b.voxels.push_back(voxel({6, y, 0}, {6.5f, y + 0.5f, 0.55f}, {0, 0, 1}, 6));
    // A box on the old ground: top at z = 1.5 (1 m over the plane), a side face upright.
    b.voxels.push_back(voxel({2, 2, 1}, {2.5f, 2.5f, 1.5f}, {0, 0, 1}, 6));
    b.voxels.push_back(voxel({1, 2, 1}, {1.9f, 2.5f, 1.2f}, {1, 0, 0}, 6));
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    const std::size_t all = 25 + b.voxels.size();
    EXPECT_EQ(merge_local_maps(a, b, I, 1024, 0.2).voxels.size(), all);  // without: every one

    std::size_t absorbed = 0, beside = 0;
    const common::LocalMapData m = merge_local_maps(a, b, I, 1024, 0.2, &absorbed, 0.5, &beside);
    EXPECT_EQ(absorbed, 0u);
    EXPECT_EQ(beside, std::size_t(ring));
    EXPECT_EQ(m.voxels.size(), 25u + 5u + 2u);
    const auto cells = by_cell(m);
    for (int y = 0; y < 5; ++y) EXPECT_TRUE(cells.count({6, y, 0})) << y;
    EXPECT_TRUE(cells.count({2, 2, 1}));
    EXPECT_TRUE(cells.count({1, 2, 1}));
    EXPECT_FALSE(cells.count({5, 2, 0}));
    EXPECT_FALSE(cells.count({-1, -1, 0}));

    // A hole in the old patch (a cell maintenance emptied): seen again, it is filled.
    common::LocalMapData holed = a;
    holed.voxels.erase(holed.voxels.begin() + 12);  // cell (2, 2, 0)
    common::LocalMapData again = b;
    again.voxels = {voxel({2, 2, 0}, {2.5f, 2.5f, 0.55f}, {0, 0, 1}, 6)};
    const common::LocalMapData filled = merge_local_maps(holed, again, I, 1024, 0.2, nullptr, 0.5);
    EXPECT_EQ(filled.voxels.size(), 25u);
    EXPECT_TRUE(by_cell(filled).count({2, 2, 0}));

    // Off the plane by more than the tolerance (0.6 m over it): a new surface, it enters.
    common::LocalMapData raised = b;
    raised.voxels = {voxel({5, 2, 1}, {5.5f, 2.5f, 1.1f}, {0, 0, 1}, 6)};
    EXPECT_EQ(merge_local_maps(a, raised, I, 1024, 0.2, nullptr, 0.5).voxels.size(), 26u);
    // Beside the patch but upright (normal along x): another surface, it enters.
    raised.voxels = {voxel({5, 2, 0}, {5.1f, 2.5f, 0.5f}, {1, 0, 0}, 6)};
    EXPECT_EQ(merge_local_maps(a, raised, I, 1024, 0.2, nullptr, 0.5).voxels.size(), 26u);
}

// The beside rule adds nothing, but the old voxel it stands beside was seen again: its life goes
// on (last_seen), so the forgetting below does not take a surface another day sees one cell on.
TEST(LocalMapMerge, AVoxelBesideTheOldSurfaceRefreshesTheOldVoxelsLastSighting) {
    common::LocalMapData a, b;
    a.voxel_size = b.voxel_size = 1.0f;
    a.observation_times = {1.0};
    b.observation_times = {86401.0};
    common::VoxelData old = voxel({0, 0, 0}, {0.5f, 0.5f, 0.5f}, {0, 0, 1}, 10);
    old.life.created = old.life.last_seen = 1.0;
    old.life.observations = 4;
    old.life.seen = {0};
    a.voxels = {old};
    common::VoxelData next = voxel({1, 0, 0}, {1.5f, 0.5f, 0.55f}, {0, 0, 1}, 6);
    next.life.created = next.life.last_seen = 86401.0;
    next.life.observations = 1;
    next.life.seen = {0};
    b.voxels = {next};
    std::size_t beside = 0;
    const common::LocalMapData m =
        merge_local_maps(a, b, Eigen::Isometry3d::Identity(), 1024, 0.2, nullptr, 0.5, &beside);
    EXPECT_EQ(beside, 1u);
    ASSERT_EQ(m.voxels.size(), 1u);
    EXPECT_DOUBLE_EQ(m.voxels[0].life.last_seen, 86401.0);
    EXPECT_DOUBLE_EQ(m.voxels[0].life.created, 1.0);
    EXPECT_EQ(m.voxels[0].life.observations, 4u);  // a sighting, not an observation of its cell
    EXPECT_EQ(m.voxels[0].life.seen, (std::vector<std::uint16_t>{0, 1}));
}

// Four days' visits of one local map (each a few scans a second apart; days apart): a voxel seen
// on day 0 only is forgotten once three later visits missed it, one seen on day 1 stays (two
// missed), one seen every day stays; a lap two minutes later is a visit of its own, scans within
// a visit are not.
TEST(LocalMapMerge, AVoxelTheLastVisitsOfItsLocalMapDidNotSeeIsForgotten) {
    common::LocalMapData m;
    m.voxel_size = 1.0f;
    for (int day = 0; day < 4; ++day)
        for (int k = 0; k < 5; ++k) m.observation_times.push_back(86400.0 * day + 0.1 * k);
    const auto seen_last = [](int x, double t) {
        common::VoxelData v = voxel({x, 0, 0}, {x + 0.5f, 0.5f, 0.5f}, {0, 0, 1}, 5);
        v.life.created = 0.0;
        v.life.last_seen = t;
        v.life.observations = 3;
        return v;
    };
    m.voxels = {seen_last(0, 0.4), seen_last(1, 86400.2), seen_last(2, 3 * 86400.0 + 0.3)};

    common::LocalMapData kept = m;
    EXPECT_EQ(forget_unseen_voxels(&kept, 0, 60.0), 0u);  // off
    EXPECT_EQ(kept.voxels.size(), 3u);
    EXPECT_EQ(forget_unseen_voxels(&kept, 4, 60.0), 0u);  // day 0's voxel missed three, not four
    common::LocalMapData three = m;
    EXPECT_EQ(forget_unseen_voxels(&three, 3, 60.0), 1u);
    ASSERT_EQ(three.voxels.size(), 2u);
    EXPECT_EQ(three.voxels[0].index.x(), 1);
    EXPECT_EQ(three.voxels[1].index.x(), 2);
    // Within one visit nothing is missed: one day's scans are one visit however many.
    common::LocalMapData one_day = m;
    one_day.observation_times = {0.0, 0.1, 0.2, 0.3, 0.4};
    one_day.voxels = {seen_last(0, 0.0), seen_last(1, 0.4)};
    EXPECT_EQ(forget_unseen_voxels(&one_day, 1, 60.0), 0u);
    // A lap later (120 s, more than the gap): a visit of its own.
    one_day.observation_times.push_back(120.0);
    EXPECT_EQ(forget_unseen_voxels(&one_day, 1, 60.0), 2u);
    EXPECT_TRUE(one_day.voxels.empty());
}

// A long day on the same ground (eight laps 100 s apart) is one visit with the default gap: a
// voxel seen on day 0 or on the day's first lap only is not forgotten within the day (with a
// 60 s gap the laps were eight visits: a long day forgot 45 k voxels of repeat_week's yard, day
// 0's far ground among them); three later days are three visits as before.
TEST(LocalMapMerge, TheLapsOfALongDayAreOneVisitWithTheDefaultGap) {
    const MapperConfig config;
    const auto& life = config.long_term;
    common::LocalMapData m;
    m.voxel_size = 1.0f;
    for (int k = 0; k < 5; ++k) m.observation_times.push_back(0.1 * k);
    for (int lap = 0; lap < 8; ++lap)
        for (int k = 0; k < 5; ++k) m.observation_times.push_back(86400.0 + 100.0 * lap + 0.1 * k);
    const auto seen_last = [](int x, double t) {
        common::VoxelData v = voxel({x, 0, 0}, {x + 0.5f, 0.5f, 0.5f}, {0, 0, 1}, 5);
        v.life.created = 0.0;
        v.life.last_seen = t;
        v.life.observations = 3;
        return v;
    };
    m.voxels = {seen_last(0, 0.4), seen_last(1, 86400.2)};
    EXPECT_EQ(forget_unseen_voxels(&m, life.forget_after_visits, life.visit_gap), 0u);
    for (int day = 2; day < 4; ++day)
        for (int k = 0; k < 5; ++k) m.observation_times.push_back(86400.0 * day + 0.1 * k);
    EXPECT_EQ(forget_unseen_voxels(&m, life.forget_after_visits, life.visit_gap), 1u);
    ASSERT_EQ(m.voxels.size(), 1u);
    EXPECT_EQ(m.voxels[0].index.x(), 1);
}

}  // namespace
}  // namespace ltm::mapping
