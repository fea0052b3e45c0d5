#pragma once
// A pose parameter of a launch config, [x, y, z, roll, pitch, yaw] (m, deg; see
// common/core/pose_xyz_rpy.hpp): an extrinsic such as a LiDAR's place on the robot.
#include <stdexcept>
#include <string>
#include <vector>

#include "common/core/pose_xyz_rpy.hpp"
#include "runtime/parameters.hpp"

namespace ltm::runtime {

// The pose at `key`, or `fallback` when absent; a wrong one fails at its line (ConfigError).
inline Eigen::Isometry3d pose_param(Parameters& p, const std::string& key,
                                    const Eigen::Isometry3d& fallback) {
    if (!p.has(key)) return fallback;
    try {
        return common::pose_from_xyz_rpy(p.get<std::vector<double>>(key, {}));
    } catch (const std::invalid_argument& e) {
        p.fail(key, e.what());
    }
}

}  // namespace ltm::runtime
