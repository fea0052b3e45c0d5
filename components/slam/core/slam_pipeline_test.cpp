#include "slam/core/slam_pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "map/core/map_store.hpp"
#include "registration/core/test_scenes.hpp"

namespace ltm::slam {
namespace {

// Along the synthetic street, 1 m a scan, weaving gently.
Eigen::Isometry3d street_pose(int i) {
    return registration::test::make_pose(1.0 * i, 0.4 * std::sin(i / 5.0), 1.8, 0.0, 0.0,
                                         3.0 * std::sin(i / 8.0));
}

TEST(SlamPipeline, HandsEveryMapAndKeyframeToTheMapperWithObservationTimes) {
    const registration::test::Scene scene = registration::test::street_scene();
    SlamPipelineConfig config;
    config.odometry.local_map.half_extent = 40.0;
    config.odometry.local_map.switch_distance = 12.0;
    config.odometry.keyframe.distance = 2.0;
    config.handover.snapshot_every_keyframes = 4;
    SlamPipeline pipeline(config);
    const int scans = 48;
    std::size_t keyframes = 0, maps = 0, tracked = 0;
    for (int i = 0; i < scans; ++i) {
        const Eigen::Isometry3d T = street_pose(i);
        common::PointCloud c =
            registration::test::scan_scene(scene, registration::test::ScanPattern(), T, T, 300 + i);
        c.stamp = 0.1 * i;
        const SlamFrame f = pipeline.process(c);
        EXPECT_EQ(f.scan_index, std::uint64_t(i));
        tracked += f.odometry.pose_valid();
        EXPECT_EQ(f.keyframe.has_value(), f.handover.keyframe.has_value());
        if (f.keyframe) {
            ++keyframes;
            EXPECT_TRUE(f.keyframe->added) << f.keyframe->message;
        }
        ASSERT_EQ(f.local_maps.size(), f.handover.local_maps.size());
        for (std::size_t k = 0; k < f.local_maps.size(); ++k) {
            EXPECT_TRUE(f.local_maps[k].added) << f.local_maps[k].message;
            EXPECT_FALSE(f.handover.local_maps[k].observation_times.empty());
            ++maps;
        }
    }
    std::vector<mapping::LocalMapResult> last;
    const mapping::OptimisationSummary s = pipeline.finish(&last);
    EXPECT_TRUE(s.solved) << s.message;
    EXPECT_FALSE(last.empty());
    EXPECT_EQ(tracked, std::size_t(scans));
    EXPECT_EQ(pipeline.mapper().keyframes().size(), keyframes);
    EXPECT_EQ(pipeline.handover().keyframes(), keyframes);
    EXPECT_GT(maps, 0u);
    // Every stored local map carries the stamps of the scans that updated it, in order.
    const map::MapData saved = pipeline.mapper().snapshot();
    ASSERT_GE(saved.local_maps.size(), 3u);
    for (const auto& m : saved.local_maps) {
        ASSERT_TRUE(m.data);
        EXPECT_TRUE(m.data->finished);
        ASSERT_FALSE(m.data->observation_times.empty()) << "map " << m.data->id;
        for (std::size_t k = 1; k < m.data->observation_times.size(); ++k)
            EXPECT_LT(m.data->observation_times[k - 1], m.data->observation_times[k]);
    }
}

// A map from a known trajectory (survey, GNSS-INS, another SLAM): every scan placed at its given
// pose, no registration, no loop closure. The map's keyframes sit exactly at the given poses.
TEST(SlamPipeline, AMapFromGivenPosesKeepsThem) {
    const registration::test::Scene scene = registration::test::street_scene();
    SlamPipelineConfig config;
    config.odometry.local_map.half_extent = 40.0;
    config.odometry.local_map.switch_distance = 12.0;
    config.odometry.keyframe.distance = 2.0;
    config.mapping.loop_closure = false;
    SlamPipeline pipeline(config);
    // Given poses a little off the ones the scans were taken at (as another system's would be).
    auto given = [](int i) {
        return street_pose(i) *
               registration::test::make_pose(0.05 * std::sin(i), 0.1, 0.02, 0.3, -0.2, 0.5 * i);
    };
    const int scans = 30;
    for (int i = 0; i < scans; ++i) {
        common::PointCloud c = registration::test::scan_scene(
            scene, registration::test::ScanPattern(), street_pose(i), street_pose(i), 300 + i);
        c.stamp = 0.1 * i;
        const SlamFrame f = pipeline.process(c, given(i));
        ASSERT_TRUE(f.odometry.pose_valid()) << f.odometry.message;
        if (f.keyframe) {
            EXPECT_TRUE(f.keyframe->added) << f.keyframe->message;
            EXPECT_FALSE(f.keyframe->verified);
            EXPECT_EQ(f.keyframe->candidates, 0u);
        }
    }
    EXPECT_TRUE(pipeline.finish().solved);
    const mapping::Mapper& mapper = pipeline.mapper();
    EXPECT_TRUE(mapper.loops().empty());
    ASSERT_GE(mapper.keyframes().size(), 12u);
    auto expect_at_given_poses = [&](const map::MapData& map, const char* what) {
        std::map<std::uint64_t, const map::PoseGraphNode*> nodes;
        for (const map::PoseGraphNode& n : map.nodes) nodes[n.id] = &n;
        for (const auto& k : map.keyframes) {
            const Eigen::Isometry3d T = nodes.at(k->node)->T_world_anchor * k->data.T_anchor_lidar;
            const Eigen::Isometry3d G = given(int(k->data.scan_index));
            EXPECT_LT((T.matrix() - G.matrix()).cwiseAbs().maxCoeff(), 1e-9)
                << what << ": keyframe of scan " << k->data.scan_index;
            EXPECT_FALSE(k->localisation_descriptor.empty());
        }
    };
    const map::MapData snapshot = mapper.snapshot();
    expect_at_given_poses(snapshot, "in the mapper");
    EXPECT_GE(snapshot.local_maps.size(), 3u);
    for (const auto& m : snapshot.local_maps) EXPECT_GT(m.data->voxels.size(), 100u);
    // Saved (format 2) and loaded again.
    const std::string dir = std::string(LTM_BINARY_DIR) + "/slam_test_maps/given_poses";
    std::filesystem::remove_all(dir);
    map::save_map(dir, snapshot);
    const map::LoadedMap loaded = map::load_map(dir);
    ASSERT_TRUE(loaded.refused.empty()) << loaded.refused.front();
    EXPECT_EQ(loaded.map.keyframes.size(), snapshot.keyframes.size());
    EXPECT_EQ(loaded.map.local_maps.size(), snapshot.local_maps.size());
    EXPECT_TRUE(map::has_localisation_descriptors(loaded.map.localisation_descriptor_config));
    expect_at_given_poses(loaded.map, "loaded");
}

}  // namespace
}  // namespace ltm::slam
