#include "runtime/convert/odometry.hpp"

#include "runtime/convert/dds_string.hpp"
#include "runtime/convert/geometry.hpp"

namespace ltm::convert {

Owned<msg::Odometry> to_msg(const OdometryData& o) {
    Owned<msg::Odometry> m;
    m->header.stamp = o.stamp;
    set_string(m->header.frame_id, o.frame_id);
    set_string(m->child_frame_id, o.child_frame_id);
    m->pose.pose = to_pose(o.T_parent_child);
    to_array36(o.pose_covariance, m->pose.covariance);
    const Eigen::Vector3d& v = o.linear_velocity;
    const Eigen::Vector3d& w = o.angular_velocity;
    m->twist.twist.linear = {v.x(), v.y(), v.z()};
    m->twist.twist.angular = {w.x(), w.y(), w.z()};
    to_array36(o.twist_covariance, m->twist.covariance);
    return m;
}

OdometryData from_msg(const msg::Odometry& m) {
    OdometryData o;
    o.stamp = m.header.stamp;
    o.frame_id = to_string(m.header.frame_id);
    o.child_frame_id = to_string(m.child_frame_id);
    o.T_parent_child = to_isometry(m.pose.pose);
    o.pose_covariance = from_array36(m.pose.covariance);
    const auto& t = m.twist.twist;
    o.linear_velocity = {t.linear.x, t.linear.y, t.linear.z};
    o.angular_velocity = {t.angular.x, t.angular.y, t.angular.z};
    o.twist_covariance = from_array36(m.twist.covariance);
    return o;
}

OdometryData reparent(OdometryData o, const Eigen::Isometry3d& T_frame_parent,
                      const std::string& frame_id) {
    o.frame_id = frame_id;
    o.T_parent_child = T_frame_parent * o.T_parent_child;
    OdometryData::Matrix6d R = OdometryData::Matrix6d::Zero();
    R.topLeftCorner<3, 3>() = R.bottomRightCorner<3, 3>() = T_frame_parent.rotation();
    o.pose_covariance = R * o.pose_covariance * R.transpose();
    return o;
}

}  // namespace ltm::convert
