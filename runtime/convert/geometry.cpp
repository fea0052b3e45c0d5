#include "runtime/convert/geometry.hpp"

#include <cmath>

namespace ltm::convert {

double to_seconds(const msg::Time& t) { return t.sec + 1e-9 * t.nanosec; }

msg::Time to_time(double seconds) {
    msg::Time t;
    double whole = std::floor(seconds);
    long long ns = std::llround((seconds - whole) * 1e9);
    if (ns >= 1000000000LL) {
        whole += 1;
        ns -= 1000000000LL;
    }
    t.sec = static_cast<std::int32_t>(whole);
    t.nanosec = static_cast<std::uint32_t>(ns);
    return t;
}

Eigen::Isometry3d to_isometry(const msg::Pose& p) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
    if (q.norm() < 1e-9) q = Eigen::Quaterniond::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
    return T;
}

msg::Pose to_pose(const Eigen::Isometry3d& T) {
    msg::Pose p;
    const Eigen::Quaterniond q(T.rotation());
    p.position = {T.translation().x(), T.translation().y(), T.translation().z()};
    p.orientation = {q.x(), q.y(), q.z(), q.w()};
    return p;
}

void to_array36(const Eigen::Matrix<double, 6, 6>& m, double out[36]) {
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) out[6 * r + c] = m(r, c);
}

Eigen::Matrix<double, 6, 6> from_array36(const double in[36]) {
    Eigen::Matrix<double, 6, 6> m;
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) m(r, c) = in[6 * r + c];
    return m;
}

}  // namespace ltm::convert
