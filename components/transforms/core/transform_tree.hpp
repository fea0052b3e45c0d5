#pragma once
// The robot's transform tree as ROS tools expect it: map -> odom -> base_link -> lidar.
// The odometry gives odom -> lidar; the base's extrinsic (base_link -> lidar, from the launch
// config) turns it into odom -> base_link; the localisation or the SLAM gives map -> odom.
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace ltm::transforms {

struct FrameNames {
    std::string map = "map", odom = "odom", base = "base_link", lidar = "lidar";
};

struct Transform {
    double stamp = 0.0;  // [s]
    std::string parent, child;
    Eigen::Isometry3d T_parent_child = Eigen::Isometry3d::Identity();
    EIGEN_MAKE_ALIGNED_OPERATOR_NEW
};

class TransformTree {
  public:
    TransformTree(FrameNames names, const Eigen::Isometry3d& T_base_lidar);

    const FrameNames& names() const { return names_; }
    // base_link -> lidar (tf_static).
    Transform static_transform() const;

    // An odometry pose (frame `odom` -> `lidar`): odom -> base_link, and map -> odom at the same
    // stamp once one is known. Empty, with `problem` set, when the frames are not the tree's or
    // the pose is not finite.
    std::vector<Transform> on_odometry(double stamp, const std::string& odom_frame,
                                       const std::string& lidar_frame,
                                       const Eigen::Isometry3d& T_odom_lidar, std::string* problem);
    // A map -> odom correction (localisation or SLAM): kept, and returned to publish now.
    std::optional<Transform> on_map_to_odom(double stamp, const std::string& map_frame,
                                            const std::string& odom_frame,
                                            const Eigen::Isometry3d& T_map_odom,
                                            std::string* problem);
    bool has_map() const { return map_to_odom_.has_value(); }

  private:
    FrameNames names_;
    Eigen::Isometry3d T_lidar_base_;
    std::optional<Transform> map_to_odom_;
};

}  // namespace ltm::transforms
