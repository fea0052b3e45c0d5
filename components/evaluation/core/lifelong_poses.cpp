#include "evaluation/core/lifelong_poses.hpp"

#include <algorithm>
#include <cmath>

#include "evaluation/core/alignment.hpp"
#include "evaluation/core/frames.hpp"
#include "evaluation/core/stats.hpp"

namespace ltm::eval {

MapAlignment fit_map_alignment(const common::Trajectory& keyframes, const common::Trajectory& truth,
                               double max_dt) {
    const PairedPoses paired = pair_by_stamp(keyframes, truth, max_dt);
    MapAlignment out;
    const AteDetail detail = compute_ate_detail(paired.estimate, paired.reference, true);
    out.T_world_map = detail.T_ref_est;
    out.ate = detail.stats;
    out.matched = paired.estimate.size();
    out.unmatched = paired.unmatched;
    return out;
}

MapSimilarity fit_map_similarity(const common::Trajectory& keyframes,
                                 const common::Trajectory& truth, double max_dt) {
    const PairedPoses paired = pair_by_stamp(keyframes, truth, max_dt);
    const std::vector<Eigen::Vector3d> est = positions(paired.estimate),
                                       ref = positions(paired.reference);
    MapSimilarity out;
    out.matched = est.size();
    out.T_world_map = umeyama_sim3(est, ref, &out.scale);
    double sum = 0.0;
    for (std::size_t i = 0; i < est.size(); ++i)
        sum += (out.T_world_map * (out.scale * est[i]) - ref[i]).squaredNorm();
    out.rmse = est.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(est.size()));
    return out;
}

common::Trajectory scaled_positions(const common::Trajectory& poses, double scale) {
    common::Trajectory out = poses;
    for (common::StampedPose& p : out) p.pose.translation() *= scale;
    return out;
}

DayPoseScore score_day_poses(const common::Trajectory& map_poses, const common::Trajectory& truth,
                             const Eigen::Isometry3d& T_world_map,
                             const std::vector<double>& kidnap_stamps,
                             const DayPoseConfig& config) {
    DayPoseScore out;
    out.scans = truth.size();
    out.error.assign(truth.size(), -1.0);
    out.aligned.assign(truth.size(), Eigen::Isometry3d::Identity());
    // Truth indices by stamp; each published pose goes to the nearest scan within max_dt (a
    // second pose for the same scan is ignored: the first one published counts).
    std::vector<std::size_t> order(truth.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return truth[a].stamp < truth[b].stamp; });
    for (const auto& p : map_poses) {
        const auto it =
            std::lower_bound(order.begin(), order.end(), p.stamp,
                             [&](std::size_t i, double s) { return truth[i].stamp < s; });
        long best = -1;
        double best_dt = config.max_dt;
        if (it != order.end()) {
            const double dt = std::abs(truth[*it].stamp - p.stamp);
            if (dt <= best_dt) best_dt = dt, best = static_cast<long>(*it);
        }
        if (it != order.begin()) {
            const std::size_t j = *(it - 1);
            const double dt = std::abs(truth[j].stamp - p.stamp);
            if (dt <= best_dt) best = static_cast<long>(j);
        }
        if (best < 0 || out.error[static_cast<std::size_t>(best)] >= 0.0) continue;
        const auto k = static_cast<std::size_t>(best);
        out.aligned[k] = T_world_map * p.pose;
        out.error[k] = (out.aligned[k].translation() - truth[k].pose.translation()).norm();
    }
    std::vector<double> errors;
    for (double e : out.error) {
        if (e < 0.0) continue;
        errors.push_back(e);
        if (e > config.wrong) ++out.wrong;
    }
    out.with_pose = errors.size();
    const ErrorStats stats = summarize(errors);
    out.rmse = stats.rmse;
    out.max = stats.max;
    out.p95 = percentile(errors, 95.0);

    for (double k : kidnap_stamps) {
        KidnapRecovery r;
        r.stamp = k;
        for (std::size_t n = 0; n < order.size(); ++n) {
            const std::size_t i = order[n];
            if (truth[i].stamp < k - config.max_dt) continue;
            const double e = out.error[i];
            if (e >= 0.0 && e <= config.wrong) {
                r.recovered = true;
                r.time_s = std::max(0.0, truth[i].stamp - k);
                break;
            }
            if (e > config.wrong) ++r.wrong;
            ++r.scans;
        }
        out.kidnaps.push_back(r);
    }
    return out;
}

}  // namespace ltm::eval
