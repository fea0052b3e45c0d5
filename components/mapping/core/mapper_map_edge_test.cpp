// A loaded map's edge (MapEdgeConfig, issue 26): a later session's keyframe that the loaded map
// explains on one side only (the map ahead is what an earlier day saw from afar, or nothing) ties
// nothing; where the map explains it all round, the same loop is tied.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "mapping/core/mapper.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::mapping {
namespace {

namespace rt = registration::test;

// Keyframes every 3 m east along y = 0 from x = -20, local maps of 4 keyframes, in an odometry
// frame T_odom_world; each keyframe sees `scene` within 50 m.
struct Road {
    common::PoseList odom;
    std::vector<std::vector<Eigen::Vector3f>> points;
    std::vector<common::LocalMapData> maps;
    double t0;

    Road(const std::vector<Eigen::Vector3f>& scene, const Eigen::Isometry3d& T_odom_world,
         double start)
        : t0(start) {
        for (std::size_t i = 0; i < 16; ++i) {
            const Eigen::Isometry3d T_world_lidar = rt::xy_yaw(-20.0 + 3.0 * double(i), 0.0, 0.0);
            odom.push_back(T_odom_world * T_world_lidar);
            points.push_back(rt::view(scene, T_world_lidar, 50.0));
        }
        for (std::uint64_t m = 0; m < 4; ++m) {
            std::vector<std::vector<Eigen::Vector3f>> scans(points.begin() + 4 * m,
                                                            points.begin() + 4 * m + 4);
            common::PoseList poses(odom.begin() + 4 * m, odom.begin() + 4 * m + 4);
            maps.push_back(rt::build_local_map(m, poses.front(), scans, poses));
            for (double& t : maps.back().observation_times) t += start;
        }
    }

    common::KeyframeData keyframe(std::size_t i) const {
        common::KeyframeData k;
        k.id = i;
        k.scan_index = i;
        k.local_map_id = i / 4;
        k.stamp = t0 + double(i);
        k.T_odom_lidar = odom[i];
        k.T_anchor_lidar = maps[i / 4].T_odom_anchor.inverse() * odom[i];
        k.points = points[i];
        return k;
    }

    // Every keyframe and local map into `mapper`; the loops it tied and why others were refused.
    std::vector<LoopClosure> drive(Mapper& mapper, std::vector<std::string>* refused) const {
        std::vector<LoopClosure> loops;
        for (std::size_t i = 0; i < 16; ++i) {
            const KeyframeResult r = mapper.add_keyframe(keyframe(i));
            EXPECT_TRUE(r.added) << r.message;
            loops.insert(loops.end(), r.loops.begin(), r.loops.end());
            for (const LoopRejection& j : r.rejected) refused->push_back(j.reason);
            if (r.optimisation_due()) {
                EXPECT_TRUE(mapper.optimise().solved);
            }
            if (i % 4 == 3) {
                EXPECT_TRUE(mapper.add_local_map(maps[i / 4]).added);
            }
        }
        return loops;
    }
};

MapperConfig edge_config(double overlap) {
    MapperConfig c;
    c.loop_detection.exclude_recent_keyframes = 6;
    c.loop_detection.exclude_recent_seconds = 0.0;
    c.loop_detection.max_distance = std::numeric_limits<double>::infinity();  // verify them all
    c.loop_detection.max_results = 1;
    c.loop_cooldown_keyframes = 0;
    c.map_edge.overlap = overlap;
    return c;
}

std::size_t count_with(const std::vector<std::string>& reasons, const std::string& text) {
    std::size_t n = 0;
    for (const std::string& r : reasons) n += r.find(text) != std::string::npos;
    return n;
}

class MapEdge : public ::testing::Test {
  protected:
    void SetUp() override {
        full_ = rt::with_dense_ground(rt::synthetic_scene(71));
        // The first day saw the site south of y = 8 only: the loaded map's edge runs along the
        // road, just north of it.
        for (const Eigen::Vector3f& p : full_)
            if (p.y() < 8.0f) south_.push_back(p);
        Mapper first(edge_config(0.5));
        std::vector<std::string> refused;
        Road(south_, Eigen::Isometry3d::Identity(), 0.0).drive(first, &refused);
        ASSERT_TRUE(first.optimise().solved);
        map_ = first.snapshot();
    }

    // A day later, the same road in another odometry frame, seeing `scene`: its loops towards the
    // loaded map (session 0).
    std::vector<LoopClosure> next_day(const std::vector<Eigen::Vector3f>& scene, double overlap,
                                      std::vector<std::string>* refused) const {
        Mapper next(edge_config(overlap), map_);
        std::vector<LoopClosure> loops =
            Road(scene, rt::xy_yaw(-30.0, 12.0, 25.0), 86400.0).drive(next, refused);
        std::vector<LoopClosure> to_map;
        for (const LoopClosure& l : loops)
            if (l.match_session == 0) to_map.push_back(l);
        return to_map;
    }

    std::vector<Eigen::Vector3f> full_, south_;
    map::MapData map_;
};

TEST_F(MapEdge, AKeyframeTheLoadedMapExplainsOnOneSideOnlyTiesNothing) {
    // Seeing the whole site, the keyframes' north is beyond the loaded map: overall the map still
    // explains enough of them for the verification, so without the rule they are tied.
    std::vector<std::string> refused_off, refused_on;
    const std::vector<LoopClosure> off = next_day(full_, 0.0, &refused_off);
    ASSERT_FALSE(off.empty()) << "without map_edge the loops are tied";
    for (const LoopClosure& l : off) {
        EXPECT_GE(l.inlier_fraction, 0.5);
        EXPECT_LT(l.min_sector_fraction, 0.5) << "the north is not in the loaded map";
    }
    EXPECT_EQ(count_with(refused_off, "edge"), 0u);
    // With it, the same keyframes tie nothing, and say why.
    const std::vector<LoopClosure> on = next_day(full_, 0.5, &refused_on);
    EXPECT_TRUE(on.empty()) << on.size() << " loops tied at the map's edge";
    EXPECT_GE(count_with(refused_on, "at the loaded map's edge"), off.size());
}

TEST_F(MapEdge, AKeyframeTheLoadedMapExplainsAllRoundIsTied) {
    // Seeing what the first day saw: explained in every direction, tied under the rule.
    std::vector<std::string> refused;
    const std::vector<LoopClosure> on = next_day(south_, 0.5, &refused);
    ASSERT_FALSE(on.empty());
    for (const LoopClosure& l : on) EXPECT_GE(l.min_sector_fraction, 0.5);
    EXPECT_EQ(count_with(refused, "edge"), 0u);
}

}  // namespace
}  // namespace ltm::mapping
