#pragma once
// Test helpers of the localisation core's tests: maps built in the test from a synthetic scene
// (exact truth), one keyframe a scan.
#include <cmath>
#include <memory>
#include <vector>

#include "localisation/core/localisation_map.hpp"
#include "map/core/map_store.hpp"
#include "registration/core/test_data.hpp"

namespace ltm::localisation::test_scene {

namespace mt = registration::test;
inline constexpr double kDeg = M_PI / 180.0;

struct Errors {
    double translation, rotation_deg;
};
inline Errors error_of(const Eigen::Isometry3d& est, const Eigen::Isometry3d& truth) {
    const Eigen::Isometry3d d = truth.inverse() * est;
    return {d.translation().norm(), Eigen::AngleAxisd(d.linear()).angle() / kDeg};
}

inline places::ScanContextConfig descriptor_config(double sensor_height) {
    places::ScanContextConfig c;
    c.kind = places::ScanContextKind::kMeanVariance;
    c.max_range = 60.0;
    c.sensor_height = sensor_height;
    return c;
}

// A map of one local map built from `scans` at `poses` (world = map frame), a keyframe a scan.
inline map::MapData make_map(const std::vector<std::vector<Eigen::Vector3f>>& scans,
                             const common::PoseList& poses, double voxel, double sensor_height) {
    map::MapData m;
    m.localisation_descriptor_config = descriptor_config(sensor_height);
    map::PoseGraphNode node;
    node.id = 0;
    node.T_world_anchor = poses.front();
    node.T_odom_anchor = poses.front();
    m.nodes.push_back(node);
    auto data = std::make_shared<common::LocalMapData>(
        mt::build_local_map(0, poses.front(), scans, poses, voxel, 80.0));
    m.local_maps.push_back({0, 0, data});
    for (std::size_t i = 0; i < scans.size(); ++i) {
        auto k = std::make_shared<map::StoredKeyframe>();
        k->node = 0;
        k->data.id = i;
        k->data.stamp = 0.1 * double(i);
        k->data.T_odom_lidar = poses[i];
        k->data.T_anchor_lidar = poses.front().inverse() * poses[i];
        k->localisation_descriptor =
            places::make_scan_context(scans[i], m.localisation_descriptor_config);
        m.keyframes.push_back(k);
    }
    return m;
}

// The synthetic scene seen along a path (every 2 m, heading along x, then turning).
struct SceneMap {
    std::vector<Eigen::Vector3f> scene;
    common::PoseList path;
    std::shared_ptr<const LocalisationMap> map;
};

inline const SceneMap& scene_map() {
    static const SceneMap s = [] {
        SceneMap r;
        r.scene = mt::with_dense_ground(mt::synthetic_scene(11, 70.0));
        std::vector<std::vector<Eigen::Vector3f>> scans;
        for (int i = 0; i < 16; ++i) {
            const double x = -15.0 + 2.0 * i;
            r.path.push_back(mt::xy_yaw(x, 0.2 * x, 5.0 * i));
            scans.push_back(mt::view(r.scene, r.path.back(), 60.0));
        }
        r.map = std::make_shared<const LocalisationMap>(make_map(scans, r.path, 0.6, 0.0));
        return r;
    }();
    return s;
}

}  // namespace ltm::localisation::test_scene
