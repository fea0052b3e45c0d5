#include "localisation/core/map_pages.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "common/core/config_check.hpp"
#include "localisation/core/global_localiser.hpp"
#include "localisation/core/localisation_map.hpp"
#include "localisation/core/localiser.hpp"
#include "localisation/core/localiser_test_scene.hpp"
#include "localisation/core/map_features.hpp"
#include "localisation/core/neighbourhood_builder.hpp"
#include "map/core/map_store.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::localisation {
namespace {

namespace fs = std::filesystem;
namespace mt = registration::test;

constexpr double kSpacing = 50.0;  // between the local maps' anchors along x [m]
constexpr int kLocalMaps = 7;      // anchors at x = 0 .. 300
constexpr double kReach = 30.0;    // a local map's half extent and the scans' range [m]

// A map longer than the radii used below: local maps anchored every kSpacing along x, each built
// from three scans around its anchor, a keyframe a scan; saved into a directory of its own.
struct LongMap {
    std::string dir;
    std::vector<Eigen::Vector3f> scene;
    std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> anchors;
    // mixed: the fourth local map on a coarser lattice (1.5 m voxels; the others 1 m).
    explicit LongMap(bool mixed = false) {
        dir = (fs::temp_directory_path() /
               ("ltm_map_pages_" + std::string(mixed ? "mixed_" : "") + std::to_string(::getpid())))
                  .string();
        fs::remove_all(dir);
        for (int s = 0; s < 4; ++s) {
            const auto part = mt::synthetic_scene(21 + s, 60.0);
            for (const auto& p : part) scene.push_back(p + Eigen::Vector3f(100.0f * s, 0, 0));
        }
        map::MapData m;
        m.localisation_descriptor_config = test_scene::descriptor_config(0.0);
        for (int i = 0; i < kLocalMaps; ++i) {
            const Eigen::Isometry3d anchor = mt::xy_yaw(kSpacing * i, 0.0, 0.0);
            anchors.push_back(anchor);
            map::PoseGraphNode node;
            node.id = std::uint64_t(10 + i);
            node.T_world_anchor = anchor;
            node.T_odom_anchor = anchor;
            m.nodes.push_back(node);
            std::vector<std::vector<Eigen::Vector3f>> scans;
            common::PoseList poses;
            for (int k = -1; k <= 1; ++k) {
                poses.push_back(mt::xy_yaw(kSpacing * i + 4.0 * k, 0.5 * k, 3.0 * k));
                scans.push_back(mt::view(scene, poses.back(), kReach));
            }
            auto data = std::make_shared<common::LocalMapData>(mt::build_local_map(
                node.id, anchor, scans, poses, mixed && i == 3 ? 1.5 : 1.0, kReach));
            m.local_maps.push_back({node.id, 0, data});
            for (std::size_t k = 0; k < scans.size(); ++k) {
                auto kf = std::make_shared<map::StoredKeyframe>();
                kf->node = node.id;
                kf->data.id = std::uint64_t(3 * i) + k;
                kf->data.stamp = double(3 * i + k);
                kf->data.T_odom_lidar = poses[k];
                kf->data.T_anchor_lidar = anchor.inverse() * poses[k];
                kf->descriptor = places::make_scan_context(scans[k], m.descriptor_config);
                kf->localisation_descriptor =
                    places::make_scan_context(scans[k], m.localisation_descriptor_config);
                m.keyframes.push_back(kf);
            }
        }
        map::save_map(dir, m);
        const auto loaded = map::load_map(dir);
        EXPECT_TRUE(loaded.refused.empty()) << loaded.refused.front();
        EXPECT_EQ(loaded.map.keyframes.size(), m.keyframes.size());
    }
    ~LongMap() { fs::remove_all(dir); }
};

const LongMap& long_map() {
    static const LongMap m;
    return m;
}

// A voxel by its exact centre (a merged voxel keeps its local map's centre, the mean of its
// points).
using Key = std::tuple<float, float, float>;
std::map<Key, const common::VoxelData*> by_centre(const common::LocalMapData& d) {
    std::map<Key, const common::VoxelData*> out;
    for (const auto& v : d.voxels) out[{v.centre.x(), v.centre.y(), v.centre.z()}] = &v;
    return out;
}

TEST(MapPages, AWholeMapRadiusIsTheLoadedMapVoxelForVoxel) {
    const LongMap& lm = long_map();
    const LocalisationMap full(map::load_map(lm.dir).map);
    MapPages pages(lm.dir);
    EXPECT_EQ(pages.local_maps(), std::size_t(kLocalMaps));
    const auto n = pages.build(Eigen::Vector3d(150, 0, 0), 1000.0);
    EXPECT_TRUE(n->complete);
    ASSERT_EQ(n->voxel_count(), full.voxels().voxels.size());
    for (std::size_t i = 0; i < n->voxels->voxels.size(); ++i) {
        EXPECT_EQ(n->voxels->voxels[i].centre, full.voxels().voxels[i].centre);
        EXPECT_EQ(n->voxels->voxels[i].normal, full.voxels().voxels[i].normal);
    }
    EXPECT_EQ(n->target->fine.usable_voxels(), full.target().fine.usable_voxels());
    // merge_all: the same voxels.
    const map::MergedVoxels all = pages.merge_all();
    ASSERT_EQ(all.voxels->voxels.size(), full.voxels().voxels.size());
    for (std::size_t i = 0; i < all.voxels->voxels.size(); ++i)
        EXPECT_EQ(all.voxels->voxels[i].centre, full.voxels().voxels[i].centre);
}

TEST(MapPages, ANeighbourhoodHoldsTheLocalMapsWithinItsRadiusAndTheirVoxelsUnchanged) {
    const LongMap& lm = long_map();
    const LocalisationMap full(map::load_map(lm.dir).map);
    MapPages pages(lm.dir);
    const Eigen::Vector3d centre(150, 0, 0);
    const double radius = 60.0;
    const auto n = pages.build(centre, radius);
    EXPECT_FALSE(n->complete);
    EXPECT_EQ(n->nodes, (std::vector<std::uint64_t>{12, 13, 14}));  // anchors 100, 150, 200
    EXPECT_LT(n->voxel_count(), full.voxels().voxels.size() / 2);
    // Every voxel held lies within the held local maps' reach; every voxel of the whole map
    // within (radius - reach) of the centre is held, identical (its nearest anchor is held).
    const auto held = by_centre(*n->voxels);
    for (const auto& v : n->voxels->voxels) {
        EXPECT_LE((v.centre.cast<double>() - centre).head<2>().norm(), radius + 1.5 * kReach);
    }
    std::size_t checked = 0;
    for (const auto& v : full.voxels().voxels) {
        if ((v.centre.cast<double>() - centre).head<2>().norm() > radius - kReach) continue;
        const auto it = held.find({v.centre.x(), v.centre.y(), v.centre.z()});
        ASSERT_NE(it, held.end());
        EXPECT_EQ(it->second->normal, v.normal);
        ++checked;
    }
    EXPECT_GT(checked, 100u);
}

// Local maps of two voxel sizes: the merge is on the larger lattice, as merge_voxels' (the build
// met the 1.5 m map after 1 m ones and merged again on its lattice).
TEST(MapPages, LocalMapsOfTwoVoxelSizesMergeAsTheLoadedMap) {
    static const LongMap lm(true);
    const LocalisationMap full(map::load_map(lm.dir).map);
    EXPECT_FLOAT_EQ(float(full.voxel_size()), 1.5f);
    const auto n = MapPages(lm.dir).build(Eigen::Vector3d(150, 0, 0), 1000.0);
    EXPECT_FLOAT_EQ(n->voxels->voxel_size, 1.5f);
    ASSERT_EQ(n->voxel_count(), full.voxels().voxels.size());
    for (std::size_t i = 0; i < n->voxels->voxels.size(); ++i) {
        EXPECT_EQ(n->voxels->voxels[i].centre, full.voxels().voxels[i].centre);
    }
}

TEST(MapPages, ADamagedLocalMapIsLeftOutAndNamedTheRestIsUsed) {
    const LongMap& lm = long_map();
    const std::string copy = lm.dir + "_damaged";
    fs::remove_all(copy);
    fs::copy(lm.dir, copy, fs::copy_options::recursive);
    std::string victim;
    for (const auto& e : fs::directory_iterator(fs::path(copy) / "local_maps")) {
        if (e.path().filename().string().rfind("lm_00000013_", 0) == 0) victim = e.path().string();
    }
    ASSERT_FALSE(victim.empty());
    {
        std::fstream f(victim, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(40);
        f.put('\x5a');
    }
    MapPages pages(copy);  // the local maps are not read here
    std::vector<std::string> refused;
    const auto n = pages.build(Eigen::Vector3d(150, 0, 0), 60.0, &refused);
    ASSERT_EQ(refused.size(), 1u);
    EXPECT_NE(refused[0].find("lm_00000013_"), std::string::npos) << refused[0];
    EXPECT_EQ(n->nodes, (std::vector<std::uint64_t>{12, 14}));
    EXPECT_GT(n->voxel_count(), 0u);
    fs::remove_all(copy);
}

TEST(NeighbourhoodBuilder, MovingAlongTheMapSwapsNeighbourhoodsHeldVoxelsStayBounded) {
    const LongMap& lm = long_map();
    auto pages = std::make_shared<const MapPages>(lm.dir);
    const std::size_t whole = pages->build(Eigen::Vector3d::Zero(), 1000.0)->voxel_count();
    // The most any neighbourhood may hold: the local maps anchored within the radius of a point
    // (at most three with anchors 50 m apart and a 60 m radius).
    std::size_t bound = 0;
    for (int i = 0; i + 2 < kLocalMaps; ++i) {
        bound = std::max(
            bound, pages->build(Eigen::Vector3d(kSpacing * (i + 1), 0, 0), 60.0)->voxel_count());
    }
    NeighbourhoodConfig config;
    config.radius = 60.0;
    config.rebuild_distance = 20.0;
    NeighbourhoodBuilder builder(pages, config, Eigen::Vector3d::Zero());
    EXPECT_EQ(builder.current()->nodes, (std::vector<std::uint64_t>{10, 11}));
    std::vector<std::vector<std::uint64_t>> seen{builder.current()->nodes};
    for (double x = 0.0; x <= 300.0; x += 5.0) {
        builder.update(Eigen::Vector3d(x, 0, 0));
        builder.settle();  // reproducible: the build asked for at x is in use from here
        if (builder.current()->nodes != seen.back()) seen.push_back(builder.current()->nodes);
        EXPECT_LE(builder.current()->voxel_count(), bound);
        EXPECT_LT(builder.current()->voxel_count(), whole);
        // The pose is never outside what is held: a local map anchored within 40 m of it is.
        bool near = false;
        for (std::uint64_t node : builder.current()->nodes) {
            near |= std::abs(kSpacing * double(node - 10) - x) <= 40.0;
        }
        EXPECT_TRUE(near) << "x " << x;
    }
    EXPECT_GE(seen.size(), std::size_t(kLocalMaps - 1));
    EXPECT_EQ(seen.back(), (std::vector<std::uint64_t>{15, 16}));
    EXPECT_GT(builder.builds(), 5u);
    EXPECT_TRUE(builder.refused().empty());
}

TEST(NeighbourhoodBuilder, AMapWithinTheRadiusIsBuiltOnceAndNeverAgain) {
    const LongMap& lm = long_map();
    auto pages = std::make_shared<const MapPages>(lm.dir);
    NeighbourhoodConfig config;
    config.radius = 1000.0;
    NeighbourhoodBuilder builder(pages, config, Eigen::Vector3d::Zero());
    EXPECT_TRUE(builder.current()->complete);
    const auto first = builder.current();
    for (double x = 0.0; x <= 300.0; x += 50.0) {
        EXPECT_FALSE(builder.update(Eigen::Vector3d(x, 0, 0)));
        builder.settle();
    }
    EXPECT_EQ(builder.current(), first);
    EXPECT_EQ(builder.builds(), 1u);
}

// Tracking along a map longer than the radius: the paged localiser swaps neighbourhoods as it goes
// and gives the poses the whole map gives (the voxels a scan meets are the same ones).
TEST(LocaliserOnAPagedMap, TrackingAlongTheMapSwapsNeighbourhoodsAndKeepsThePose) {
    const LongMap& lm = long_map();
    auto whole = std::make_shared<const LocalisationMap>(map::load_map(lm.dir).map);
    auto pages = std::make_shared<const MapPages>(lm.dir);
    NeighbourhoodConfig nc;
    nc.radius = 100.0;  // the scans reach 30 m, the pose is within 20 m of the centre asked
    nc.rebuild_distance = 20.0;
    Localiser paged(whole), unpaged(whole);
    auto builder = std::make_shared<NeighbourhoodBuilder>(pages, nc, Eigen::Vector3d::Zero());
    paged.set_neighbourhood(builder);
    const std::size_t all = whole->voxels().voxels.size();
    std::vector<std::vector<std::uint64_t>> seen{builder->current()->nodes};
    std::size_t compared = 0;
    for (int i = 0; i <= 150; ++i) {
        const Eigen::Isometry3d truth =
            mt::xy_yaw(2.0 * i, 0.3 * std::sin(0.1 * i), 2.0 * std::sin(0.05 * i));
        const auto scan = mt::view(lm.scene, truth, kReach);
        if (i == 0) {
            paged.set_initial_pose({truth, 5.0});
            unpaged.set_initial_pose({truth, 5.0});
        }
        const OdometryInput odom{truth, 0};
        const LocalisationUpdate a = paged.process(0.1 * i, scan, odom);
        const LocalisationUpdate b = unpaged.process(0.1 * i, scan, odom);
        builder->settle();  // reproducible: the neighbourhood asked for is in use from here
        if (builder->current()->nodes != seen.back()) seen.push_back(builder->current()->nodes);
        EXPECT_LT(builder->current()->voxel_count(), all);
        ASSERT_EQ(a.state, b.state) << "scan " << i << ": " << a.message << " / " << b.message;
        ASSERT_EQ(a.pose_valid, b.pose_valid) << "scan " << i;
        if (!b.pose_valid) continue;
        EXPECT_LT((a.T_map_lidar.matrix() - b.T_map_lidar.matrix()).cwiseAbs().maxCoeff(), 1e-6)
            << "scan " << i;
        EXPECT_LT(test_scene::error_of(a.T_map_lidar, truth).translation, 0.3) << "scan " << i;
        ++compared;
    }
    EXPECT_GT(compared, 140u);
    EXPECT_GE(seen.size(), 4u);  // it moved from {10, 11, 12} to {14, 15, 16}
    EXPECT_EQ(seen.front(), (std::vector<std::uint64_t>{10, 11, 12}));
    EXPECT_EQ(seen.back(), (std::vector<std::uint64_t>{14, 15, 16}));
}

// A fix far from the neighbourhood in use (here: the builder started at the map's other end): the
// pose follows the odometry while the build asked for is pending (off the map, not lost), and
// tracking resumes on the new neighbourhood.
TEST(LocaliserOnAPagedMap, AFixFarFromTheNeighbourhoodWaitsForItsBuildNotLost) {
    const LongMap& lm = long_map();
    auto whole = std::make_shared<const LocalisationMap>(map::load_map(lm.dir).map);
    NeighbourhoodConfig nc;
    nc.radius = 100.0;
    nc.rebuild_distance = 20.0;
    auto builder = std::make_shared<NeighbourhoodBuilder>(std::make_shared<const MapPages>(lm.dir),
                                                          nc, Eigen::Vector3d(300, 0, 0));
    Localiser paged(whole);
    paged.set_neighbourhood(builder);
    EXPECT_FALSE(builder->holds(Eigen::Vector3d(0, 0, 0)));
    std::vector<LocalisationUpdate> u;
    for (int i = 0; i < 4; ++i) {
        const Eigen::Isometry3d truth = mt::xy_yaw(1.0 * i, 0.0, 0.0);
        if (i == 0) paged.set_initial_pose({truth, 5.0});
        u.push_back(
            paged.process(0.1 * i, mt::view(lm.scene, truth, kReach), OdometryInput{truth, 0}));
        if (i == 1) builder->settle();
        EXPECT_LT(test_scene::error_of(u.back().T_map_lidar, truth).translation, 0.3) << i;
    }
    EXPECT_EQ(u[0].state, LocalisationState::kRelocalised);  // global: the whole map
    EXPECT_EQ(u[1].state, LocalisationState::kOffMap) << u[1].message;
    EXPECT_NE(u[1].message.find("loading"), std::string::npos) << u[1].message;
    EXPECT_TRUE(u[1].pose_valid);
    EXPECT_TRUE(builder->holds(Eigen::Vector3d(2, 0, 0)));
    EXPECT_EQ(u[2].state, LocalisationState::kTracking) << u[2].message;
    EXPECT_EQ(u[3].state, LocalisationState::kTracking) << u[3].message;
}

// A paged map keeps the site's index (keyframes, descriptors, local features) and a coverage
// grid, and lets its voxels go: they are read back from the directory where a query needs them.
TEST(PagedLocalisationMap, KeepsTheSiteIndexAndLetsTheVoxelsGo) {
    const LongMap& lm = long_map();
    const auto whole = load_localisation_map(lm.dir);
    const auto paged = load_localisation_map(lm.dir, {}, nullptr, 100.0);
    EXPECT_FALSE(whole->paged());
    ASSERT_TRUE(paged->paged());
    // A map whose local-map files hold less than page_above_mb is held whole.
    EXPECT_FALSE(load_localisation_map(lm.dir, {}, nullptr, 100.0, 1000.0)->paged());
    EXPECT_TRUE(load_localisation_map(lm.dir, {}, nullptr, 100.0, 1e-6)->paged());
    EXPECT_THROW(paged->voxels(), common::ConfigError);
    EXPECT_THROW(paged->target(), common::ConfigError);
    EXPECT_GE(paged->voxel_count(), whole->voxel_count());  // the local maps' voxels, summed
    EXPECT_EQ(paged->voxel_size(), whole->voxel_size());
    EXPECT_EQ(paged->coarse_voxel_size(), whole->target().coarse->voxel_size());
    ASSERT_EQ(paged->keyframes().size(), whole->keyframes().size());
    // No local features kept: a query makes those of its places from the local maps it reads,
    // the same samples as the whole map's there.
    EXPECT_EQ(paged->feature_count(), 0u);
    EXPECT_TRUE(paged->has_features());
    ASSERT_GT(whole->feature_count(), 0u);
    const Eigen::Vector3d place(150, 0, 0);
    const auto around = paged->neighbourhood_around({place});
    ASSERT_TRUE(around);
    const places::LocalFeatures made = paged->features_around(*around, {place}, 40.0);
    const places::LocalFeatures kept = whole->features_near(place, 20.0);
    ASSERT_GT(kept.size(), 10u);
    std::size_t found = 0;
    for (std::size_t i = 0; i < kept.size(); ++i) {
        for (std::size_t j = 0; j < made.size(); ++j) {
            if (made.positions[j] != kept.positions[i]) continue;
            EXPECT_EQ(made.descriptors[j].value, kept.descriptors[i].value) << i;
            EXPECT_EQ(made.descriptors[j].spread, kept.descriptors[i].spread) << i;
            ++found;
        }
    }
    EXPECT_EQ(found, kept.size());  // every sample within 20 m, made again the same
    // covers(): the same answers on the map, beside it and far from it (the coverage grid's 2 m
    // cells may say yes up to a cell's diagonal farther: none of these points is that close).
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(150, 5, 0), Eigen::Vector3d(300, -5, 0),
          Eigen::Vector3d(150, 200, 0), Eigen::Vector3d(-200, 0, 0), Eigen::Vector3d(500, 0, 0)}) {
        for (double r : {1.0, 5.0, 20.0})
            EXPECT_EQ(paged->covers(p, r), whole->covers(p, r)) << p.transpose() << " r " << r;
    }
    // A query's target: the local maps near its initial poses only.
    const auto near_start = paged->target_around({Eigen::Vector3d(0, 0, 0)});
    ASSERT_TRUE(near_start);
    EXPECT_LT(near_start->fine.usable_voxels(), whole->target().fine.usable_voxels());
    EXPECT_EQ(whole->target_around({Eigen::Vector3d(0, 0, 0)}).get(), &whole->target());
}

// Global queries on a paged map verify on the local maps near their initial poses: where those
// hold everything the scan sees (scans reach 30 m, local maps 30 m, radius 100 m) the answers
// are the whole map's.
TEST(PagedLocalisationMap, GlobalQueriesAnswerAsOnTheWholeMap) {
    const LongMap& lm = long_map();
    const auto whole = load_localisation_map(lm.dir);
    const auto paged = load_localisation_map(lm.dir, {}, nullptr, 100.0);
    GlobalLocaliser a(whole), b(paged);
    int localised = 0;
    for (double x : {20.0, 95.0, 160.0, 230.0, 290.0}) {
        const Eigen::Isometry3d truth = mt::xy_yaw(x, 1.5, 40.0);
        const auto scan = mt::view(lm.scene, truth, kReach);
        const GlobalLocalisation ra = a.localise(scan);
        const GlobalLocalisation rb = b.localise(scan);
        ASSERT_EQ(ra.localised, rb.localised) << x << ": " << ra.reason << " / " << rb.reason;
        EXPECT_EQ(ra.verified, rb.verified) << x;
        if (!ra.localised) continue;
        ++localised;
        EXPECT_LT((ra.T_map_lidar.matrix() - rb.T_map_lidar.matrix()).cwiseAbs().maxCoeff(), 1e-6)
            << x;
        EXPECT_LT(test_scene::error_of(rb.T_map_lidar, truth).translation, 0.3) << x;
        const GlobalLocalisation va = a.verify(scan, truth), vb = b.verify(scan, truth);
        EXPECT_EQ(va.localised, vb.localised) << x;
        EXPECT_EQ(va.inliers, vb.inliers) << x;
    }
    EXPECT_GE(localised, 4);
}

// The whole mission on a paged map: tracking on the neighbourhood, a kidnap to the map's other
// end relocalised by a global query on the pages there, then tracked there at once on the local
// maps the query read (NeighbourhoodBuilder::adopt), no build of its own.
TEST(LocaliserOnAPagedMap, AKidnapAcrossTheMapIsRelocalisedFromThePages) {
    const LongMap& lm = long_map();
    const auto paged = load_localisation_map(lm.dir, {}, nullptr, 100.0);
    NeighbourhoodConfig nc;
    nc.radius = 100.0;
    nc.rebuild_distance = 20.0;
    auto builder =
        std::make_shared<NeighbourhoodBuilder>(paged->pages(), nc, Eigen::Vector3d::Zero());
    LocaliserConfig config;
    config.lost_after = 0.25;
    Localiser localiser(paged, config);
    localiser.set_neighbourhood(builder);
    localiser.set_initial_pose({mt::xy_yaw(0, 0, 0), 5.0});
    double stamp = 0.0;
    int tracked_after = 0;
    bool relocalised = false;
    for (int i = 0; i < 40; ++i) {
        // 10 scans near the start, then the robot is carried to x = 270 (the odometry does not
        // know: its pose goes on from where it was).
        const Eigen::Isometry3d truth =
            i < 10 ? mt::xy_yaw(0.5 * i, 0, 0) : mt::xy_yaw(270.0 + 0.5 * (i - 10), 1.0, 30.0);
        const Eigen::Isometry3d odom = mt::xy_yaw(0.5 * i, 0, 0);
        const LocalisationUpdate u =
            localiser.process(stamp, mt::view(lm.scene, truth, kReach), OdometryInput{odom, 0});
        stamp += 0.1;
        builder->settle();
        if (i < 10) {
            if (i > 0) {
                EXPECT_EQ(u.state, LocalisationState::kTracking) << i << ": " << u.message;
            }
            continue;
        }
        if (u.state == LocalisationState::kRelocalised) relocalised = true;
        if (relocalised && u.pose_valid) {
            // From the relocalisation on, every pose is at the new place.
            EXPECT_LT(test_scene::error_of(u.T_map_lidar, truth).translation, 0.5)
                << i << ": " << u.message;
        }
        if (relocalised && u.state == LocalisationState::kTracking) ++tracked_after;
        if (relocalised) {
            // Tracked at once on the local maps the answer was verified on: never off the map
            // waiting for a build.
            EXPECT_NE(u.state, LocalisationState::kOffMap) << i << ": " << u.message;
        }
    }
    EXPECT_TRUE(relocalised);
    EXPECT_GE(tracked_after, 25);
    EXPECT_TRUE(builder->holds(Eigen::Vector3d(280, 0, 0)));
    EXPECT_EQ(builder->builds(), 1u);  // the start's only: the kidnap's place was adopted
}

TEST(NeighbourhoodConfig, OutOfRangeValuesAreRejectedWithOneLine) {
    NeighbourhoodConfig c;
    EXPECT_NO_THROW(validate(c));
    c.radius = -1.0;
    EXPECT_THROW(validate(c), common::ConfigError);
    c.radius = 100.0;
    c.rebuild_distance = 100.0;
    EXPECT_THROW(validate(c), common::ConfigError);
    c.rebuild_distance = 0.0;
    EXPECT_THROW(validate(c), common::ConfigError);
    c.radius = 0.0;  // no paging: rebuild_distance unused
    EXPECT_NO_THROW(validate(c));
    c.page_above_mb = -1.0;
    EXPECT_THROW(validate(c), common::ConfigError);
    // The localiser's keys: neighbourhood.radius, neighbourhood.rebuild_distance.
    LocaliserConfig lc;
    EXPECT_FALSE(validate(lc).has_value());
    EXPECT_EQ(lc.neighbourhood.radius, 0.0);  // off by default
    lc.neighbourhood.radius = 50.0;
    lc.neighbourhood.rebuild_distance = 60.0;
    const auto problem = validate(lc);
    ASSERT_TRUE(problem.has_value());
    EXPECT_EQ(problem->key, "neighbourhood.rebuild_distance");
    lc.neighbourhood.radius = -5.0;
    ASSERT_TRUE(validate(lc).has_value());
    EXPECT_EQ(validate(lc)->key, "neighbourhood.radius");
    EXPECT_THROW(Localiser(std::shared_ptr<const LocalisationMap>(), lc), common::ConfigError);
}

}  // namespace
}  // namespace ltm::localisation
