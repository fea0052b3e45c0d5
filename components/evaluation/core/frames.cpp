#include "evaluation/core/frames.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ltm::eval {

common::PoseList camera_to_lidar(const common::PoseList& camera_poses,
                                 const Eigen::Isometry3d& T_cam_lidar) {
    return common::camera_to_lidar_poses(camera_poses, T_cam_lidar);
}

common::PoseList lidar_to_camera(const common::PoseList& lidar_poses,
                                 const Eigen::Isometry3d& T_cam_lidar) {
    return common::camera_to_lidar_poses(lidar_poses, T_cam_lidar.inverse());
}

common::PoseList poses_of(const common::Trajectory& trajectory) {
    common::PoseList out;
    out.reserve(trajectory.size());
    for (const auto& sp : trajectory) out.push_back(sp.pose);
    return out;
}

PairedPoses pair_by_stamp(const common::Trajectory& estimate, const common::Trajectory& reference,
                          double max_dt) {
    // Reference indices sorted by stamp; binary search for each estimate stamp.
    std::vector<std::size_t> order(reference.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return reference[a].stamp < reference[b].stamp;
    });
    std::vector<double> stamps;
    stamps.reserve(order.size());
    for (std::size_t i : order) stamps.push_back(reference[i].stamp);
    std::vector<bool> used(reference.size(), false);

    PairedPoses out;
    for (const auto& e : estimate) {
        const auto it = std::lower_bound(stamps.begin(), stamps.end(), e.stamp);
        const auto k = static_cast<long>(it - stamps.begin());
        long best = -1;
        double best_dt = max_dt;
        // The nearest unused neighbours on either side.
        for (long j = k; j < static_cast<long>(stamps.size()); ++j) {
            if (stamps[j] - e.stamp > best_dt) break;
            if (!used[order[j]]) {
                best_dt = std::abs(stamps[j] - e.stamp);
                best = j;
                break;
            }
        }
        for (long j = k - 1; j >= 0; --j) {
            if (e.stamp - stamps[j] > best_dt) break;
            if (!used[order[j]]) {
                if (e.stamp - stamps[j] <= best_dt) best = j;
                break;
            }
        }
        if (best < 0) {
            ++out.unmatched;
            continue;
        }
        used[order[best]] = true;
        out.estimate.push_back(e.pose);
        out.reference.push_back(reference[order[best]].pose);
        out.stamps.push_back(e.stamp);
    }
    return out;
}

}  // namespace ltm::eval
