#include "registration/core/se3.hpp"

#include <cmath>

namespace ltm::registration {
namespace {

Eigen::Matrix3d hat(const Eigen::Vector3d& v) {
    Eigen::Matrix3d m;
    m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return m;
}

// V of the SE(3) exponential: t = V(phi) rho.
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& phi) {
    const double theta = phi.norm();
    const Eigen::Matrix3d W = hat(phi);
    if (theta < 1e-6) return Eigen::Matrix3d::Identity() + 0.5 * W + W * W / 6.0;
    const double t2 = theta * theta;
    return Eigen::Matrix3d::Identity() + (1.0 - std::cos(theta)) / t2 * W +
           (theta - std::sin(theta)) / (t2 * theta) * W * W;
}

}  // namespace

Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi) {
    const double theta = phi.norm();
    if (theta < 1e-12) return Eigen::Matrix3d::Identity() + hat(phi);
    return Eigen::AngleAxisd(theta, phi / theta).toRotationMatrix();
}

Eigen::Vector3d so3_log(const Eigen::Matrix3d& R) {
    const Eigen::AngleAxisd aa(R);
    return aa.angle() * aa.axis();
}

Eigen::Isometry3d se3_exp(const Vector6d& xi) {
    const Eigen::Vector3d phi = xi.tail<3>();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = so3_exp(phi);
    T.translation() = left_jacobian(phi) * xi.head<3>();
    return T;
}

Vector6d se3_log(const Eigen::Isometry3d& T) {
    const Eigen::Vector3d phi = so3_log(T.linear());
    Vector6d xi;
    xi.head<3>() = left_jacobian(phi).inverse() * T.translation();
    xi.tail<3>() = phi;
    return xi;
}

Eigen::Isometry3d scale_motion(const Eigen::Isometry3d& T, double s) {
    if (s == 1.0) return T;
    return se3_exp(s * se3_log(T));
}

double rotation_angle(const Eigen::Isometry3d& T) { return Eigen::AngleAxisd(T.linear()).angle(); }

}  // namespace ltm::registration
