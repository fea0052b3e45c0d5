#include "evaluation/core/ate.hpp"

#include <algorithm>

#include "evaluation/core/alignment.hpp"
#include "evaluation/core/stats.hpp"

namespace ltm::eval {

std::vector<Eigen::Vector3d> positions(const common::PoseList& poses) {
    std::vector<Eigen::Vector3d> out;
    out.reserve(poses.size());
    for (const auto& p : poses) out.push_back(p.translation());
    return out;
}

common::PoseList transform_poses(const Eigen::Isometry3d& T, const common::PoseList& poses) {
    common::PoseList out;
    out.reserve(poses.size());
    for (const auto& p : poses) out.push_back(T * p);
    return out;
}

AteDetail compute_ate_detail(const common::PoseList& estimate, const common::PoseList& reference,
                             bool align) {
    const std::size_t n = std::min(estimate.size(), reference.size());
    std::vector<Eigen::Vector3d> est = positions(estimate), ref = positions(reference);
    est.resize(n);
    ref.resize(n);

    AteDetail d;
    if (align) d.T_ref_est = umeyama_se3(est, ref);
    d.errors.reserve(n);
    for (std::size_t i = 0; i < n; ++i) d.errors.push_back((d.T_ref_est * est[i] - ref[i]).norm());
    const ErrorStats s = summarize(d.errors);
    d.stats = AteResult{s.rmse, s.mean, s.median, s.max, s.n};
    return d;
}

AteResult compute_ate(const common::PoseList& estimate, const common::PoseList& reference,
                      bool align) {
    return compute_ate_detail(estimate, reference, align).stats;
}

}  // namespace ltm::eval
