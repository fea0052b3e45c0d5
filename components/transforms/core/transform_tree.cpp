#include "transforms/core/transform_tree.hpp"

#include <cmath>

namespace ltm::transforms {

namespace {

bool finite(const Eigen::Isometry3d& T) { return T.matrix().allFinite(); }

}  // namespace

TransformTree::TransformTree(FrameNames names, const Eigen::Isometry3d& T_base_lidar)
    : names_(std::move(names)), T_lidar_base_(T_base_lidar.inverse()) {}

Transform TransformTree::static_transform() const {
    Transform t;
    t.parent = names_.base;
    t.child = names_.lidar;
    t.T_parent_child = T_lidar_base_.inverse();
    return t;
}

std::vector<Transform> TransformTree::on_odometry(double stamp, const std::string& odom_frame,
                                                  const std::string& lidar_frame,
                                                  const Eigen::Isometry3d& T_odom_lidar,
                                                  std::string* problem) {
    if (odom_frame != names_.odom || lidar_frame != names_.lidar) {
        *problem = "odometry from '" + odom_frame + "' to '" + lidar_frame + "', the tree has '" +
                   names_.odom + "' -> '" + names_.lidar + "' (set odom_frame / lidar_frame)";
        return {};
    }
    if (!finite(T_odom_lidar) || !std::isfinite(stamp)) {
        *problem = "an odometry pose that is not finite";
        return {};
    }
    std::vector<Transform> out;
    if (map_to_odom_) {
        Transform m = *map_to_odom_;
        m.stamp = stamp;
        out.push_back(m);
    }
    Transform t;
    t.stamp = stamp;
    t.parent = names_.odom;
    t.child = names_.base;
    t.T_parent_child = T_odom_lidar * T_lidar_base_;
    out.push_back(t);
    return out;
}

std::optional<Transform> TransformTree::on_map_to_odom(double stamp, const std::string& map_frame,
                                                       const std::string& odom_frame,
                                                       const Eigen::Isometry3d& T_map_odom,
                                                       std::string* problem) {
    if (map_frame != names_.map || odom_frame != names_.odom) {
        *problem = "map_to_odom from '" + map_frame + "' to '" + odom_frame + "', the tree has '" +
                   names_.map + "' -> '" + names_.odom + "'";
        return std::nullopt;
    }
    if (!finite(T_map_odom) || !std::isfinite(stamp)) {
        *problem = "a map_to_odom that is not finite";
        return std::nullopt;
    }
    Transform t;
    t.stamp = stamp;
    t.parent = names_.map;
    t.child = names_.odom;
    t.T_parent_child = T_map_odom;
    map_to_odom_ = t;
    return t;
}

}  // namespace ltm::transforms
