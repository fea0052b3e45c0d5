#include "evaluation/core/rpe.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::eval {

double rotation_angle(const Eigen::Matrix3d& R) {
    // atan2 of the axis part and the trace part stays accurate near 0 and pi, unlike acos alone.
    const double s =
        0.5 * Eigen::Vector3d(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1)).norm();
    const double c = 0.5 * (R.trace() - 1.0);
    return std::atan2(s, c);
}

void rpe_errors(const common::PoseList& est, const common::PoseList& ref, std::size_t delta,
                std::vector<double>& translation_m, std::vector<double>& rotation_deg) {
    translation_m.clear();
    rotation_deg.clear();
    if (delta == 0) delta = 1;
    const std::size_t n = std::min(est.size(), ref.size());
    for (std::size_t i = 0; i + delta < n; ++i) {
        const Eigen::Isometry3d d_ref = ref[i].inverse() * ref[i + delta];
        const Eigen::Isometry3d d_est = est[i].inverse() * est[i + delta];
        const Eigen::Isometry3d e = d_ref.inverse() * d_est;
        translation_m.push_back(e.translation().norm());
        rotation_deg.push_back(rotation_angle(e.linear()) * 180.0 / M_PI);
    }
}

RpeResult compute_rpe(const common::PoseList& est, const common::PoseList& ref, std::size_t delta) {
    RpeResult r;
    r.delta = delta == 0 ? 1 : delta;
    std::vector<double> t, a;
    rpe_errors(est, ref, r.delta, t, a);
    r.translation = summarize(t);
    r.rotation_deg = summarize(a);
    return r;
}

}  // namespace ltm::eval
