#include "odometry/core/observability.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace ltm::odometry {

Observability translation_observability(const registration::Matrix6d& H, double weak_information) {
    Observability o;
    const double weight = H.topLeftCorner<3, 3>().trace();
    if (!(weight > 0.0) || !H.allFinite()) return o;
    const Eigen::Matrix3d Htt = H.topLeftCorner<3, 3>();
    const Eigen::Matrix3d Htr = H.topRightCorner<3, 3>();
    Eigen::Matrix3d Hrr = H.bottomRightCorner<3, 3>();
    // A rotation the scan does not constrain at all cannot absorb anything: regularised.
    Hrr += Eigen::Matrix3d::Identity() * (1e-9 * std::max(Hrr.trace(), 1e-12));
    const Eigen::Matrix3d S = (Htt - Htr * Hrr.ldlt().solve(Htr.transpose())) / weight;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (S + S.transpose()));
    if (eig.info() != Eigen::Success) return o;
    o.information = eig.eigenvalues().cwiseMax(0.0);
    o.directions = eig.eigenvectors();
    for (int i = 0; i < 3; ++i) o.constrained += o.information[i] >= weak_information;
    return o;
}

registration::Matrix6d honest_covariance(const registration::Matrix6d& fit,
                                         const ObservabilityConfig& config) {
    registration::Matrix6d c = config.covariance_scale * fit;
    const double f2 = config.covariance_floor * config.covariance_floor;
    for (int i = 0; i < 3; ++i) c(i, i) += f2;
    return c;
}

void inflate_weak(const Observability& o, const Eigen::Matrix3d& R_odom_map,
                  const Eigen::Vector3d& fixed, double sigma, registration::Matrix6d* covariance) {
    for (int i = 0; i < 3 - o.constrained; ++i) {
        const Eigen::Vector3d u = R_odom_map * o.directions.col(i);
        if (std::abs(u.dot(fixed)) > 0.9) continue;
        covariance->topLeftCorner<3, 3>() += sigma * sigma * u * u.transpose();
    }
}

}  // namespace ltm::odometry
