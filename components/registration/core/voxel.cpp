#include "registration/core/voxel.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace ltm::registration {
namespace {

// The normal of covariance C from the previous normal by inverse iteration (adj(C) ~ C^-1, and it
// also handles a singular C), then the in-plane eigenvalues in closed form: a few dozen flops
// instead of a full eigen-decomposition. Each step shrinks the angle error by l_min / l_mid, so
// for the plane-like voxels that matter three steps are exact to float precision. False when
// the iteration degenerates (the caller then decomposes C fully).
bool refine_normal(const Eigen::Matrix3d& C, const Eigen::Vector3f& previous,
                   Eigen::Vector3f* normal, Eigen::Vector3d* eigenvalues) {
    Eigen::Matrix3d adj;
    adj(0, 0) = C(1, 1) * C(2, 2) - C(1, 2) * C(1, 2);
    adj(0, 1) = C(0, 2) * C(1, 2) - C(0, 1) * C(2, 2);
    adj(0, 2) = C(0, 1) * C(1, 2) - C(0, 2) * C(1, 1);
    adj(1, 1) = C(0, 0) * C(2, 2) - C(0, 2) * C(0, 2);
    adj(1, 2) = C(0, 1) * C(0, 2) - C(0, 0) * C(1, 2);
    adj(2, 2) = C(0, 0) * C(1, 1) - C(0, 1) * C(0, 1);
    adj(1, 0) = adj(0, 1);
    adj(2, 0) = adj(0, 2);
    adj(2, 1) = adj(1, 2);
    Eigen::Vector3d n = previous.cast<double>();
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d x = adj * n;
        const double norm = x.norm();
        if (!(norm > 1e-300) || !x.allFinite()) return false;
        n = x / norm;
    }
    const Eigen::Vector3d a = n.unitOrthogonal(), b = n.cross(a);
    const double caa = a.dot(C * a), cab = a.dot(C * b), cbb = b.dot(C * b);
    const double mean = 0.5 * (caa + cbb),
                 half = std::sqrt(0.25 * (caa - cbb) * (caa - cbb) + cab * cab);
    const double l0 = std::max(0.0, n.dot(C * n));
    const double l1 = std::max(0.0, mean - half), l2 = mean + half;
    if (l0 > l1) return false;  // not the smallest: decompose fully
    *eigenvalues = Eigen::Vector3d(l0, l1, l2);
    *normal = n.cast<float>();
    return true;
}

}  // namespace

Eigen::Matrix3d VoxelSums::covariance() const {
    const double w = weight;
    const Eigen::Vector3d m = sum.cast<double>() / w;
    Eigen::Matrix3d c;
    c << sum_sq[0], sum_sq[1], sum_sq[2], sum_sq[1], sum_sq[3], sum_sq[4], sum_sq[2], sum_sq[4],
        sum_sq[5];
    return c / w - m * m.transpose();
}

void update_surfel(const VoxelConfig& config, float voxel_size, const Eigen::Vector3f& cell_centre,
                   const Eigen::Vector3f& sensor, VoxelRecord& record, Surfel& surfel) {
    VoxelSums& sums = record.sums;
    if (sums.weight > config.max_points) sums.scale(float(config.max_points / sums.weight));
    surfel.centre = cell_centre + sums.mean();
    if (sums.weight < config.min_points_for_normal) {
        surfel.usable = 0;
        return;
    }
    Eigen::Vector3d l;  // eigenvalues, ascending
    Eigen::Vector3f n;
    if (!(surfel.normal.squaredNorm() > 0.0f &&
          refine_normal(sums.covariance(), surfel.normal, &n, &l))) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
        eig.computeDirect(sums.covariance());
        l = eig.eigenvalues().cwiseMax(0.0);
        n = eig.eigenvectors().col(0).cast<float>().normalized();
    }
    const float planarity = l[1] > 0.0 ? float(1.0 - l[0] / l[1]) : 0.0f;
    if (!n.allFinite()) {
        surfel.usable = 0;
        return;
    }
    const Eigen::Vector3f n_old = surfel.normal;  // zero before the voxel's first normal
    if (n_old.squaredNorm() > 0.0f) {
        if (n.dot(n_old) < 0.0f) n = -n;
        surfel.stability = std::abs(n.dot(n_old));
    } else {
        if (n.dot(sensor - surfel.centre) < 0.0f) n = -n;
        surfel.stability = float(config.initial_stability);
    }
    record.previous_normal = n_old;
    surfel.normal = n;
    surfel.planarity = planarity;
    const double extent = config.min_extent * voxel_size;
    surfel.usable = planarity >= config.min_planarity && l[1] >= extent * extent ? 1u : 0u;
}

}  // namespace ltm::registration
