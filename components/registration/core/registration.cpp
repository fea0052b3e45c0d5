#include "registration/core/registration.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace ltm::registration {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr std::size_t kGrain = 256;  // points a chunk of the parallel loop

// The upper triangle of H += w J J^T, element for element the arithmetic of Eigen's
// selfadjointView<Upper>().rankUpdate(J, w) (column i: H(0..i, i) += (w J_i) J(0..i)), unrolled:
// Eigen's general loop was a function call a point with a mispredicted branch per column.
inline void add_rank_one(float w, const Eigen::Matrix<float, 6, 1>& J,
                         Eigen::Matrix<float, 6, 6>* H) {
    for (int i = 0; i < 6; ++i) {
        const float a = w * J[i];
        for (int r = 0; r <= i; ++r) (*H)(r, i) += a * J[r];
    }
}

}  // namespace

const char* to_string(RegistrationResult::Status status) {
    switch (status) {
        case RegistrationResult::Status::kConverged:
            return "converged";
        case RegistrationResult::Status::kNotConverged:
            return "not converged";
        case RegistrationResult::Status::kTooFewCorrespondences:
            return "too few correspondences";
        case RegistrationResult::Status::kNumericalFailure:
            return "numerical failure";
    }
    return "unknown";
}

Registration::Registration(const RegistrationConfig& config, double voxel_size,
                           ParallelFor* parallel)
    : config_(config), parallel_(parallel) {
    imls_.bandwidth = float(config.imls_bandwidth * voxel_size);
    imls_.max_distance = float(config.max_correspondence_distance);
    imls_.min_normal_agreement = float(config.min_normal_agreement);
}

void Registration::for_chunks(std::size_t n,
                              const std::function<void(std::size_t, std::size_t, std::size_t)>& f) {
    if (parallel_) {
        parallel_->run(n, kGrain, f);
        return;
    }
    for (std::size_t c = 0; c < ParallelFor::chunk_count(n, kGrain); ++c) {
        f(c, c * kGrain, std::min(n, (c + 1) * kGrain));
    }
}

void Registration::linearise(const std::vector<Eigen::Vector3f>& points, const VoxelGrid& grid,
                             const Eigen::Isometry3d& T, Accumulator* total) {
    const std::size_t n = points.size();
    residuals_.resize(n);
    const Eigen::Matrix3f R = T.linear().cast<float>();
    const Eigen::Vector3f t = T.translation().cast<float>();
    const float min_stability = float(config_.min_stability);
    const bool stability = config_.stability_weighting;
    // Pass 1: the IMLS residual and its Jacobian at every point (the expensive part).
    for_chunks(n, [&](std::size_t, std::size_t begin, std::size_t end) {
        ImlsResult r;
        for (std::size_t i = begin; i < end; ++i) {
            Residual& out = residuals_[i];
            out.weight = 0.0f;
            const Eigen::Vector3f q = R * points[i];  // the point relative to the sensor
            const Eigen::Vector3f x = q + t;
            if (!cached_imls(cache_[i], grid, x, &r)) continue;
            out.error = r.distance;
            const float s = stability ? std::max(r.stability, min_stability) : 1.0f;
            out.weight = s * s;
            out.J.head<3>() = r.normal;
            out.J.tail<3>() = q.cross(r.normal);
        }
    });
    // Kernel scale: the configured floor, or wider while the residuals are still large (a start
    // far from the solution), from their median.
    abs_errors_.clear();
    for (const Residual& r : residuals_) {
        if (r.weight > 0.0f) abs_errors_.push_back(std::abs(r.error));
    }
    double scale = config_.kernel_scale;
    if (!abs_errors_.empty()) {
        auto mid = abs_errors_.begin() + abs_errors_.size() / 2;
        std::nth_element(abs_errors_.begin(), mid, abs_errors_.end());
        scale = std::max(scale, config_.kernel_adaptive_factor * double(*mid));
    }
    kernel_used_ = scale;
    const float s2 = float(scale * scale);
    // Pass 2: Geman-McClure weighted normal equations, float sums per chunk, double across.
    partial_.assign(ParallelFor::chunk_count(n, kGrain), Accumulator());
    for_chunks(n, [&](std::size_t c, std::size_t begin, std::size_t end) {
        Eigen::Matrix<float, 6, 6> H = Eigen::Matrix<float, 6, 6>::Zero();
        Eigen::Matrix<float, 6, 1> b = Eigen::Matrix<float, 6, 1>::Zero();
        Accumulator& acc = partial_[c];
        for (std::size_t i = begin; i < end; ++i) {
            const Residual& r = residuals_[i];
            if (r.weight <= 0.0f) continue;
            const float e = r.error;
            const float k = s2 / (s2 + e * e);
            const float w = k * k * r.weight;
            add_rank_one(w, r.J, &H);
            b += (w * e) * r.J;
            acc.weighted_sq += double(w) * e * e;
            acc.weight += w;
            acc.plain_sq += double(e) * e;
            ++acc.count;
        }
        acc.H = H.cast<double>().selfadjointView<Eigen::Upper>();
        acc.b = b.cast<double>();
    });
    *total = Accumulator();
    for (const Accumulator& a : partial_) total->add(a);
}

bool Registration::cached_imls(NeighbourCache& c, const VoxelGrid& grid, const Eigen::Vector3f& x,
                               ImlsResult* result) const {
    VoxelKey key;
    if (!grid.key_of(x, &key)) return false;
    if (key != c.key) {
        c.key = key;
        c.count = usable_neighbours(grid, x, c.index);
    }
    return imls_from_neighbours(grid.surfels(), c.index, c.count, x, imls_, result);
}

bool Registration::imls_after_align(std::size_t i, const VoxelGrid& grid, const Eigen::Vector3f& x,
                                    ImlsResult* result) {
    if (i >= cache_.size()) return imls_distance(grid, x, imls_, result);
    return cached_imls(cache_[i], grid, x, result);
}

// Normalised Hessian: rotation as displacement at the lever arm L, divided by the total weight,
// so that an eigenvalue is the weighted mean of (J.v)^2 (1/3 per axis for isotropic normals).
Registration::Spectrum Registration::spectrum(const Accumulator& acc) const {
    Spectrum s;
    const double L = config_.degeneracy_length;
    s.d << 1, 1, 1, 1 / L, 1 / L, 1 / L;
    s.weight = std::max(acc.weight, 1e-12);
    const Matrix6d Hn = s.d.asDiagonal() * acc.H * s.d.asDiagonal() / s.weight;
    s.eig.computeDirect(Hn);
    if (s.eig.info() != Eigen::Success) s.eig.compute(Hn);
    return s;
}

RegistrationResult Registration::align(const std::vector<Eigen::Vector3f>& points,
                                       const VoxelGrid& grid, const Eigen::Isometry3d& guess) {
    RegistrationResult result;
    Eigen::Isometry3d T = guess;
    cache_.assign(points.size(), NeighbourCache());
    Accumulator acc;
    const double eps_t = config_.convergence_translation;
    const double eps_r = config_.convergence_rotation * kDegToRad;
    bool converged = false;
    for (int it = 0; it < config_.max_iterations; ++it) {
        linearise(points, grid, T, &acc);
        result.iterations = it + 1;
        if (acc.count < std::size_t(config_.min_correspondences)) break;
        // Solution remapping: the step only in the well-constrained directions, so that a
        // degenerate direction stays at the prediction instead of drifting.
        const Spectrum sp = spectrum(acc);
        const Vector6d bn = sp.d.asDiagonal() * acc.b / sp.weight;
        Vector6d step_n = Vector6d::Zero();
        for (int i = 0; i < 6; ++i) {
            const double lambda = sp.eig.eigenvalues()[i];
            if (lambda < config_.degeneracy_ratio) continue;
            const auto v = sp.eig.eigenvectors().col(i);
            step_n -= v * (v.dot(bn) / lambda);
        }
        const Vector6d step = sp.d.asDiagonal() * step_n;
        if (!step.allFinite()) {
            result.status = RegistrationResult::Status::kNumericalFailure;
            result.T_map_lidar = T;
            return result;
        }
        T.linear() = (so3_exp(step.tail<3>()) * T.linear()).eval();
        T.translation() += step.head<3>();
        result.last_step_translation = step.head<3>().norm();
        result.last_step_rotation = step.tail<3>().norm();
        if (result.last_step_translation < eps_t && result.last_step_rotation < eps_r) {
            converged = true;
            break;
        }
    }
    // Keep the rotation orthonormal after many small updates.
    T.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
    result.T_map_lidar = T;
    result.points = points.size();
    result.correspondences = acc.count;
    const float inlier = float(config_.inlier_distance);
    for (const Residual& r : residuals_) {
        result.inliers += (r.weight > 0.0f && std::abs(r.error) < inlier);
    }
    result.kernel_scale = kernel_used_;
    result.residual_rms = acc.count ? std::sqrt(acc.plain_sq / double(acc.count)) : 0.0;
    if (acc.count < std::size_t(config_.min_correspondences)) {
        result.status = RegistrationResult::Status::kTooFewCorrespondences;
        return result;
    }
    result.status = converged ? RegistrationResult::Status::kConverged
                              : RegistrationResult::Status::kNotConverged;
    analyse(acc, &result);
    return result;
}

void Registration::analyse(const Accumulator& acc, RegistrationResult* result) const {
    result->hessian = acc.H;
    const Spectrum sp = spectrum(acc);
    const Vector6d lambda = sp.eig.eigenvalues();  // ascending
    result->min_information = lambda[0];
    for (int i = 0; i < 6; ++i) {
        if (lambda[i] < config_.degeneracy_ratio) {
            result->degenerate_directions.push_back(sp.eig.eigenvectors().col(i).normalized());
        }
    }
    // Covariance sigma^2 H^-1, eigenvalues floored so that a degenerate direction gets a large but
    // finite variance.
    const double dof = std::max(1.0, acc.weight - 6.0);
    const double sigma2 = acc.weighted_sq / dof;
    Vector6d inv;
    for (int i = 0; i < 6; ++i) inv[i] = 1.0 / std::max(lambda[i], 1e-6);
    const Matrix6d Hn_inv =
        sp.eig.eigenvectors() * inv.asDiagonal() * sp.eig.eigenvectors().transpose();
    result->covariance = sigma2 / sp.weight * (sp.d.asDiagonal() * Hn_inv * sp.d.asDiagonal());
}

}  // namespace ltm::registration
