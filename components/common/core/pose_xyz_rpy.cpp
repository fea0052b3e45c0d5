#include "common/core/pose_xyz_rpy.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ltm::common {

Eigen::Isometry3d pose_from_xyz_rpy(const std::vector<double>& v) {
    if (v.size() != 6) {
        throw std::invalid_argument("expected [x, y, z, roll, pitch, yaw] (m, deg), got " +
                                    std::to_string(v.size()) + " values");
    }
    for (const double x : v) {
        if (!std::isfinite(x)) throw std::invalid_argument("a value is not a finite number");
    }
    constexpr double kDeg = M_PI / 180.0;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = (Eigen::AngleAxisd(v[5] * kDeg, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(v[4] * kDeg, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(v[3] * kDeg, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    return T;
}

}  // namespace ltm::common
