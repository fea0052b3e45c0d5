#include "odometry/core/spin_hold.hpp"

#include <Eigen/QR>
#include <cmath>

namespace ltm::odometry {

void RecentTurnRate::add(double rate, double dt, double window) {
    if (!(dt > 0.0) || !std::isfinite(rate)) return;
    const double gain = window > 0.0 ? 1.0 - std::exp(-dt / window) : 1.0;
    rate_ += gain * (rate - rate_);
}

double turn_rate(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to, double dt) {
    if (!(dt > 0.0)) return 0.0;
    return registration::rotation_angle(from.inverse() * to) * 180.0 / M_PI / dt;
}

double hold_along(const Eigen::Vector3d& anchor, const std::vector<Eigen::Vector3d>& directions,
                  Eigen::Isometry3d* pose) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> U(3, 0);
    for (const Eigen::Vector3d& v : directions) {
        if (!(v.norm() > 1e-9)) continue;
        U.conservativeResize(3, U.cols() + 1);
        U.col(U.cols() - 1) = v.normalized();
    }
    if (U.cols() == 0) return 0.0;
    // An orthonormal basis of the span (rank-revealing: two nearly equal directions count once),
    // then the offset from the anchor projected onto it removed.
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(U);
    qr.setThreshold(1e-3);  // directions within ~0.06 deg of each other are one
    const Eigen::Index rank = qr.rank();
    if (rank == 0) return 0.0;
    const Eigen::MatrixXd Q = Eigen::MatrixXd(qr.householderQ()).leftCols(rank);
    const Eigen::Vector3d off = pose->translation() - anchor;
    const Eigen::Vector3d along = Q * (Q.transpose() * off);
    pose->translation() -= along;
    return along.norm();
}

bool turn_unobserved(const std::vector<registration::Vector6d>& directions,
                     const Eigen::Vector3d& axis) {
    if (directions.empty() || !(axis.norm() > 0.0)) return false;
    Eigen::MatrixXd U(6, Eigen::Index(directions.size()));
    for (std::size_t k = 0; k < directions.size(); ++k) U.col(Eigen::Index(k)) = directions[k];
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(U);
    qr.setThreshold(1e-3);
    const Eigen::Index rank = qr.rank();
    if (rank == 0) return false;
    const Eigen::MatrixXd Q = Eigen::MatrixXd(qr.householderQ()).leftCols(rank);
    registration::Vector6d w = registration::Vector6d::Zero();
    w.tail<3>() = axis.normalized();
    return (Q.transpose() * w).norm() > 0.7;
}

std::vector<Eigen::Vector3d> translation_parts(
    const std::vector<registration::Vector6d>& directions) {
    std::vector<Eigen::Vector3d> out;
    for (const registration::Vector6d& v : directions) {
        if (v.head<3>().norm() > 0.7) out.push_back(v.head<3>().normalized());
    }
    return out;
}

}  // namespace ltm::odometry
