#pragma once
// Trajectory files of a host run read by its tests: the poses of a TUM file by their stamp in
// milliseconds (the writers' stamps, so two files of one run meet on the same keys), and the
// map-to-world alignment of a run's SLAM keyframes on the truth at the same stamps.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/core/trajectory_io.hpp"
#include "evaluation/core/alignment.hpp"

namespace ltm::tests {

inline std::map<long long, Eigen::Isometry3d> poses_by_stamp_ms(const std::string& tum_file) {
    std::map<long long, Eigen::Isometry3d> out;
    for (const common::StampedPose& p : common::read_tum_trajectory(tum_file))
        out[std::llround(p.stamp * 1000.0)] = p.pose;
    return out;
}

// T_world_map from the positions of `slam_tum` and `truth_tum` at their common stamps (at least
// 10 expected).
inline Eigen::Isometry3d map_to_world(const std::string& slam_tum, const std::string& truth_tum) {
    const auto truth = poses_by_stamp_ms(truth_tum);
    std::vector<Eigen::Vector3d> est, ref;
    for (const auto& [t, T] : poses_by_stamp_ms(slam_tum)) {
        const auto it = truth.find(t);
        if (it == truth.end()) continue;
        est.push_back(T.translation());
        ref.push_back(it->second.translation());
    }
    EXPECT_GE(est.size(), 10u) << slam_tum << " and " << truth_tum << " share few stamps";
    return eval::umeyama_se3(est, ref);
}

}  // namespace ltm::tests
