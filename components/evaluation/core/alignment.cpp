#include "evaluation/core/alignment.hpp"

#include <Eigen/SVD>
#include <algorithm>

namespace ltm::eval {

namespace {

// Umeyama's fit; *scale (when given) becomes the similarity's scale, else the fit is rigid.
Eigen::Isometry3d umeyama(const std::vector<Eigen::Vector3d>& est,
                          const std::vector<Eigen::Vector3d>& ref, double* scale) {
    const std::size_t n = std::min(est.size(), ref.size());
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    if (scale) *scale = 1.0;
    if (n == 0) return T;

    Eigen::Vector3d mean_est = Eigen::Vector3d::Zero(), mean_ref = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
        mean_est += est[i];
        mean_ref += ref[i];
    }
    mean_est /= static_cast<double>(n);
    mean_ref /= static_cast<double>(n);

    // Cross-covariance Sigma = 1/n sum (ref - mean_ref)(est - mean_est)^T.
    Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < n; ++i)
        sigma += (ref[i] - mean_ref) * (est[i] - mean_est).transpose();
    sigma /= static_cast<double>(n);

    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
    // Reflection guard (Umeyama eq. 39-40): flip the weakest axis when det(U V^T) < 0.
    if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2, 2) = -1.0;
    const Eigen::Matrix3d R = svd.matrixU() * S * svd.matrixV().transpose();

    double s = 1.0;
    if (scale) {
        // Umeyama eq. 42: s = tr(D S) / sigma_est^2.
        double var_est = 0.0;
        for (std::size_t i = 0; i < n; ++i) var_est += (est[i] - mean_est).squaredNorm();
        var_est /= static_cast<double>(n);
        if (var_est > 1e-18) s = svd.singularValues().dot(S.diagonal()) / var_est;
        *scale = s;
    }
    T.linear() = R;
    T.translation() = mean_ref - s * R * mean_est;
    return T;
}

}  // namespace

Eigen::Isometry3d umeyama_se3(const std::vector<Eigen::Vector3d>& est,
                              const std::vector<Eigen::Vector3d>& ref) {
    return umeyama(est, ref, nullptr);
}

Eigen::Isometry3d umeyama_sim3(const std::vector<Eigen::Vector3d>& est,
                               const std::vector<Eigen::Vector3d>& ref, double* scale) {
    double s = 1.0;
    const Eigen::Isometry3d T = umeyama(est, ref, &s);
    if (scale) *scale = s;
    return T;
}

}  // namespace ltm::eval
