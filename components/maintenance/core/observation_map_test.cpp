#include "maintenance/core/observation_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <tuple>

namespace ltm::maintenance {
namespace {

// Points on the walls and floor of a 30 m x 30 m yard, in region (0, 0).
std::vector<Eigen::Vector3f> yard_points(std::mt19937& rng, int n) {
    std::uniform_real_distribution<float> u(0.5f, 30.0f), h(0.0f, 3.0f);
    std::vector<Eigen::Vector3f> pts;
    for (int i = 0; i < n; ++i) {
        switch (i % 3) {
            case 0:
                pts.emplace_back(u(rng), u(rng), 0.0f);
                break;
            case 1:
                pts.emplace_back(0.5f, u(rng), h(rng));
                break;
            default:
                pts.emplace_back(u(rng), 30.0f, h(rng));
                break;
        }
    }
    return pts;
}

TEST(ObservationMap, EveryPointFindsItsVoxelInUnder100BytesAVoxel) {
    MaintenanceConfig c;
    ObservationMap map(c, {0, 0});
    std::mt19937 rng(2);
    std::set<std::tuple<int, int, int>> cells;
    std::vector<Eigen::Vector3f> all;
    for (int scan = 0; scan < 20; ++scan) {
        const std::vector<Eigen::Vector3f> pts = yard_points(rng, 5000);
        map.add_points(pts, 0.1 * scan);
        for (const Eigen::Vector3f& p : pts) {
            const Eigen::Vector3f q = p / float(c.voxel_size);
            cells.insert({int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z()))});
            all.push_back(p);
        }
    }
    ASSERT_EQ(map.size(), cells.size());
    for (const Eigen::Vector3f& p : all) {
        const std::uint32_t i = map.find(p);
        ASSERT_NE(i, ObservationMap::kNone);
        EXPECT_LE((map.centre(i) - map.cell_centre(i)).cwiseAbs().maxCoeff(),
                  0.5f * map.voxel_size())
            << "a centre inside its cell";
    }
    // Judged by views: histories fill, the state stays the same size.
    View view;
    view.T_world_sensor.translation() = Eigen::Vector3d(15, 15, 1);
    std::vector<Eigen::Vector3f> in_sensor;
    for (const Eigen::Vector3f& p : yard_points(rng, 20000))
        in_sensor.push_back(p - Eigen::Vector3f(15, 15, 1));
    view.image = RangeImage(c.range_image, in_sensor);
    const std::size_t before = map.memory_bytes();
    std::size_t said = 0;
    for (int k = 0; k < 30; ++k) {
        view.map_time = 0.5 * k;
        const JudgeCounts counts = map.judge(view);
        said += counts.hit + counts.free;
    }
    EXPECT_GT(said, 30 * map.size() / 4) << "the views judged most voxels";
    EXPECT_EQ(map.memory_bytes(), before);
    EXPECT_LE(double(map.memory_bytes()) / double(map.size()), 100.0);
    // Half erased: the rest still found, the erased not.
    std::vector<bool> remove(map.size());
    for (std::size_t i = 0; i < remove.size(); i += 2) remove[i] = true;
    std::vector<registration::VoxelKey> kept, gone;
    for (std::uint32_t i = 0; i < map.size(); ++i) (remove[i] ? gone : kept).push_back(map.key(i));
    map.erase(remove);
    ASSERT_EQ(map.size(), kept.size());
    const auto at = [&](registration::VoxelKey k) {
        return ((registration::unpack_key(k).cast<float>().array() + 0.5f) * map.voxel_size())
            .matrix()
            .eval();
    };
    for (registration::VoxelKey k : kept) EXPECT_NE(map.find(at(k)), ObservationMap::kNone);
    for (registration::VoxelKey k : gone) EXPECT_EQ(map.find(at(k)), ObservationMap::kNone);
    EXPECT_LE(double(map.memory_bytes()) / double(map.size()), 100.0);
}

// The points of a fence at x = 10.1 m, y in [-1.9, 1.9], between heights z0 and z1 (world).
std::vector<Eigen::Vector3f> fence_points(float z0, float z1) {
    std::vector<Eigen::Vector3f> pts;
    for (float y = -1.9f; y <= 1.9f; y += 0.05f)
        for (float z = z0; z <= z1; z += 0.05f) pts.emplace_back(10.1f, y, z);
    return pts;
}

// A 16-beam scan (+-15 deg, 2 deg apart) from 1 m above flat ground, in the sensor frame, after
// the fence was taken down: the downward beams hit the ground, the upward ones the sky but for a
// building wall at y = -8 m (azimuth -100..-80 deg).
std::vector<Eigen::Vector3f> scan_without_fence() {
    std::vector<Eigen::Vector3f> pts;
    for (int ring = 0; ring < 16; ++ring) {
        const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0;
        for (int k = 0; k < 1800; ++k) {
            const double az_deg = -180.0 + 0.2 * k + 0.1, az = az_deg * M_PI / 180.0;
            const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                    std::sin(el));
            double t = 1e9;
            if (d.z() < 0.0) t = -1.0 / d.z();
            if (az_deg > -100.0 && az_deg < -80.0) t = std::min(t, -8.0 / d.y());
            if (t < 100.0) pts.push_back((d * t).cast<float>());
        }
    }
    return pts;
}

// A removed object above the sensor with sky behind it: the beams through its upper half return
// nothing, and they are what says it is gone (its lower half has the ground behind it).
TEST(ObservationMap, TheSkyBehindARemovedFenceSeesThroughItsUpperHalf) {
    const auto seen_through = [](const RangeImageConfig& image_config, float z0, float z1) {
        MaintenanceConfig c;
        c.range_image = image_config;
        ObservationMap map(c, {0, -1});
        map.add_points(fence_points(z0, z1), 0.0);
        View view;
        view.T_world_sensor.translation() = Eigen::Vector3d(0, 0, 1);  // sensor 1 m up
        view.map_time = 1.0;
        view.image = RangeImage(image_config, scan_without_fence());
        const JudgeCounts counts = map.judge(view);
        EXPECT_EQ(counts.hit, 0u);
        return double(counts.free) / double(std::max<std::size_t>(counts.voxels, 1));
    };
    const RangeImageConfig sky;  // the defaults
    RangeImageConfig no_sky;
    no_sky.sky_range = 0.0;
    const double lower = seen_through(sky, 0.05f, 0.5f), upper = seen_through(sky, 1.5f, 2.0f);
    EXPECT_GT(lower, 0.3) << "the ground behind the lower half";
    EXPECT_GT(upper, 0.8 * lower) << "the sky behind the upper half";
    EXPECT_EQ(seen_through(no_sky, 1.5f, 2.0f), 0.0) << "without the sky rule: never judged";
    EXPECT_EQ(seen_through(no_sky, 0.05f, 0.5f), lower);
}

// Points of a vertical patch at x (y0..y1, z0..z1), 5 cm apart.
std::vector<Eigen::Vector3f> patch_points(float x, float y0, float y1, float z0, float z1) {
    std::vector<Eigen::Vector3f> pts;
    for (float y = y0; y <= y1; y += 0.05f)
        for (float z = z0; z <= z1; z += 0.05f) pts.emplace_back(x, y, z);
    return pts;
}

// A scan from the origin (beams 0.4 deg apart, +-6 deg; 0.2 deg across) of a wall at x = 33.05 m,
// y 0.5..4.5, z -1.5..1.5: nothing else returns.
std::vector<Eigen::Vector3f> far_wall_scan() {
    std::vector<Eigen::Vector3f> pts;
    for (int ring = 0; ring <= 30; ++ring) {
        const double el = (-6.0 + 0.4 * ring) * M_PI / 180.0;
        for (int k = 0; k < 100; ++k) {
            const double az = (0.1 + 0.2 * k) * M_PI / 180.0;
            const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                    std::sin(el));
            const Eigen::Vector3d q = d * (33.05 / d.x());
            if (q.y() > 0.5 && q.y() < 4.5 && std::abs(q.z()) < 1.5) pts.push_back(q.cast<float>());
        }
    }
    return pts;
}

// A van's side 0.7 m in front of its neighbour's (a wall at 33 m here; the cube's centre 0.675 m
// in front of it, as van 75's of repeat_week) was "hit" by the
// neighbour's returns after the van left: they came back within the view's margin (0.3 m + half
// the cube's diagonal + 1 cm a metre: 0.85 m at 33 m) of its cubes. Seen from the route 33 m
// away, with the neighbour behind, those were the only views the van's side had on the day it
// left (repeat_week day 1, van 75: kept for good). A return that far behind the cube is another
// surface: neither a hit nor a view through it (hit_margin); the wall stays hit, a cube 2 m in
// front of it is seen through as before.
TEST(ObservationMap, ASurfaceJustBehindACubeIsNotAHitOnIt) {
    const auto judge = [](const MaintenanceConfig& c) {
        ObservationMap map(c, {0, 0});
        map.add_points(patch_points(32.3f, 1.5f, 3.5f, -0.5f, 0.5f), 0.0);   // the van that left
        map.add_points(patch_points(33.05f, 1.0f, 4.0f, -1.0f, 1.0f), 0.0);  // the one behind it
        map.add_points(patch_points(31.0f, 1.5f, 2.0f, 0.0f, 0.5f), 0.0);    // 2 m in front
        View view;
        view.map_time = 100.0;
        view.image = RangeImage(c.range_image, far_wall_scan());
        map.judge(view);
        std::map<int, std::pair<std::size_t, std::size_t>> by_x;  // hits, free by the cube's x
        for (std::uint32_t i = 0; i < map.size(); ++i) {
            auto& [hits, free] = by_x[int(std::lround(map.centre(i).x()))];
            for (const auto& e : map.voxel(i).hit_histogram())
                if (e.slot > 0) hits += e.count;
            for (const auto& e : map.voxel(i).free_histogram()) free += e.count;
        }
        return by_x;
    };
    MaintenanceConfig c;
    auto now = judge(c);
    EXPECT_EQ(now[32].first, 0u) << "the van's side: no hit from the wall behind it";
    EXPECT_EQ(now[32].second, 0u) << "nor seen through (the wall is within the view's margin)";
    EXPECT_GT(now[33].first, 50u) << "the wall is hit";
    EXPECT_GT(now[31].second, 2u) << "2 m in front: seen through";
    EXPECT_EQ(now[31].first, 0u);
    c.hit_margin = c.free_margin;  // the rule before: every return within the margin is a hit
    c.hit_margin_per_m = c.free_margin_per_m;
    auto before = judge(c);
    EXPECT_GT(before[32].first, 10u);
    EXPECT_EQ(before[33].first, now[33].first);
    EXPECT_EQ(before[31].second, now[31].second);
}

// A wall along the route (y = 2.1 m) seen at a grazing angle from the origin, its returns lost
// at x 29.5..30.45 m (a dark patch): the beams through the cubes there return on the same wall
// 0.3-1 m behind them. That is the voxel's own surface (on its plane), still a hit; only another
// surface just behind a cube says nothing (above).
TEST(ObservationMap, AGrazingWallsOwnReturnJustBehindItsCubeIsStillAHit) {
    MaintenanceConfig c;
    ObservationMap map(c, {0, 0});
    std::vector<Eigen::Vector3f> wall;
    for (float x = 20.0f; x <= 40.0f; x += 0.05f)
        for (float z = -0.5f; z <= 0.5f; z += 0.05f) wall.emplace_back(x, 2.1f, z);
    map.add_points(wall, 0.0);
    std::vector<Eigen::Vector3f> scan;
    for (int ring = 0; ring <= 30; ++ring) {
        const double el = (-6.0 + 0.4 * ring) * M_PI / 180.0;
        for (int k = 0; k < 100; ++k) {
            const double az = (0.1 + 0.2 * k) * M_PI / 180.0;
            const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                    std::sin(el));
            const Eigen::Vector3d q = d * (2.1 / d.y());
            if (q.x() < 20.0 || q.x() > 40.0 || std::abs(q.z()) > 0.5) continue;
            if (q.x() > 29.5 && q.x() < 30.45) continue;  // lost
            scan.push_back(q.cast<float>());
        }
    }
    View view;
    view.map_time = 100.0;
    view.image = RangeImage(c.range_image, scan);
    map.judge(view);
    std::size_t in_patch = 0, hit = 0, free = 0;
    for (std::uint32_t i = 0; i < map.size(); ++i) {
        const Eigen::Vector3f p = map.centre(i);
        if (p.x() < 29.6f || p.x() > 30.2f || std::abs(p.z()) > 0.3f) continue;
        ++in_patch;
        for (const auto& e : map.voxel(i).hit_histogram())
            if (e.slot > 0) ++hit;
        for (const auto& e : map.voxel(i).free_histogram()) free += e.count;
    }
    ASSERT_GT(in_patch, 4u);
    EXPECT_GE(hit, in_patch) << "the wall's own return just behind its cubes: hits";
    EXPECT_EQ(free, 0u);
}

}  // namespace
}  // namespace ltm::maintenance
