#include "odometry/core/step_search.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::odometry {

DirectionalSupport directional_support(const std::vector<Eigen::Vector3f>& points,
                                       const registration::VoxelGrid& grid,
                                       const registration::ImlsParams& imls,
                                       const Eigen::Isometry3d& T, const Eigen::Vector3d& v,
                                       double kernel) {
    DirectionalSupport s;
    const Eigen::Matrix3f R = T.linear().cast<float>();
    const Eigen::Vector3f t = T.translation().cast<float>();
    const Eigen::Vector3f vf = v.cast<float>();
    const float k2 = float(kernel * kernel);
    registration::ImlsResult r;
    for (const Eigen::Vector3f& p : points) {
        if (!registration::imls_distance(grid, R * p + t, imls, &r)) continue;
        if (std::abs(r.normal.dot(vf)) < 0.5f) continue;
        const float e2 = r.distance * r.distance;
        const float w = k2 / (k2 + e2);
        s.support += double(w * w);
        ++s.points;
    }
    return s;
}

Profile search_along(const std::vector<Eigen::Vector3f>& points,
                     const registration::VoxelGrid& grid, const registration::ImlsParams& imls,
                     const Eigen::Isometry3d& T_start, const Eigen::Vector3d& v,
                     const ProfileRequest& q) {
    Profile p;
    const auto eval = [&](double o) {
        Eigen::Isometry3d T = T_start;
        T.translation() += o * v;
        ++p.evaluations;
        return directional_support(points, grid, imls, T, v, q.kernel).support;
    };
    const double spacing = std::max(q.spacing, 0.05);
    const int n = std::max(1, int(std::ceil((q.to - q.from) / spacing)));
    for (int i = 0; i <= n; ++i) {
        const double o = q.from + (q.to - q.from) * double(i) / double(n);
        p.offsets.push_back(o);
        p.support.push_back(eval(o));
    }
    std::size_t best = 0;
    for (std::size_t i = 1; i < p.support.size(); ++i) {
        if (p.support[i] > p.support[best]) best = i;
    }
    p.best_offset = p.offsets[best];
    p.best_support = p.support[best];
    // Refine: every spacing / 4 within one coarse spacing of the best.
    const double fine = spacing / 4.0;
    const double centre = p.best_offset;
    for (int k = -3; k <= 3; ++k) {
        if (k == 0 || (k % 4) == 0) continue;
        const double o = centre + k * fine;
        const double s = eval(o);
        p.offsets.push_back(o);
        p.support.push_back(s);
        if (s > p.best_support) {
            p.best_support = s;
            p.best_offset = o;
        }
    }
    for (std::size_t i = 0; i < p.offsets.size(); ++i) {
        if (std::abs(p.offsets[i] - p.best_offset) > q.peak_width) {
            p.rival_support = std::max(p.rival_support, p.support[i]);
        }
    }
    // Ascending offsets for the reader.
    std::vector<std::size_t> order(p.offsets.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return p.offsets[a] < p.offsets[b]; });
    std::vector<double> o2, s2;
    for (std::size_t i : order) {
        o2.push_back(p.offsets[i]);
        s2.push_back(p.support[i]);
    }
    p.offsets.swap(o2);
    p.support.swap(s2);
    return p;
}

}  // namespace ltm::odometry
