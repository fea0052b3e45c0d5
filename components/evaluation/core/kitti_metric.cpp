#include "evaluation/core/kitti_metric.hpp"

#include <algorithm>
#include <cmath>

#include "evaluation/core/rpe.hpp"

namespace ltm::eval {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The first frame whose distance exceeds dist[first] + len; -1 when none.
long last_frame_from_length(const std::vector<double>& dist, std::size_t first, double len) {
    for (std::size_t i = first; i < dist.size(); ++i)
        if (dist[i] > dist[first] + len) return static_cast<long>(i);
    return -1;
}

}  // namespace

std::vector<double> kitti_lengths() { return {100, 200, 300, 400, 500, 600, 700, 800}; }
std::vector<double> kitti_short_lengths() { return {10, 20, 30, 40, 50}; }

std::vector<double> distances_travelled(const common::PoseList& poses) {
    std::vector<double> dist(poses.size(), 0.0);
    for (std::size_t i = 1; i < poses.size(); ++i)
        dist[i] = dist[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
    return dist;
}

std::vector<KittiSegmentError> kitti_segment_errors(const common::PoseList& est,
                                                    const common::PoseList& ref,
                                                    const std::vector<double>& lengths,
                                                    std::size_t step) {
    const std::size_t n = std::min(est.size(), ref.size());
    const common::PoseList ref_n(ref.begin(), ref.begin() + static_cast<long>(n));
    const std::vector<double> dist = distances_travelled(ref_n);
    std::vector<KittiSegmentError> out;
    if (step == 0) step = 1;
    for (std::size_t first = 0; first < n; first += step) {
        for (double len : lengths) {
            const long last = last_frame_from_length(dist, first, len);
            if (last < 0) continue;
            const auto l = static_cast<std::size_t>(last);
            const Eigen::Isometry3d delta_ref = ref[first].inverse() * ref[l];
            const Eigen::Isometry3d delta_est = est[first].inverse() * est[l];
            const Eigen::Isometry3d error = delta_est.inverse() * delta_ref;
            KittiSegmentError e;
            e.first_frame = first;
            e.last_frame = l;
            e.length = len;
            e.translation = error.translation().norm() / len;
            // The devkit takes acos((trace - 1) / 2); for the tiny angles of a segment error that
            // loses most digits when the file's rotations are rounded to 7 digits (KITTI's), so the
            // same angle is computed with the robust atan2 form.
            e.rotation = rotation_angle(error.linear()) / len;
            out.push_back(e);
        }
    }
    return out;
}

KittiMetric kitti_metric_for_lengths(const common::PoseList& est, const common::PoseList& ref,
                                     const std::vector<double>& lengths, std::size_t step) {
    const std::vector<KittiSegmentError> errors = kitti_segment_errors(est, ref, lengths, step);
    KittiMetric m;
    m.segments = errors.size();
    if (errors.empty()) return m;
    double t = 0.0, r = 0.0;
    for (const auto& e : errors) {
        t += e.translation;
        r += e.rotation;
    }
    const auto count = static_cast<double>(errors.size());
    m.translation_pct = 100.0 * t / count;
    m.rotation_deg_per_100m = 100.0 * (r / count) * 180.0 / kPi;
    return m;
}

KittiMetric compute_kitti_metric(const common::PoseList& est, const common::PoseList& ref) {
    const std::size_t n = std::min(est.size(), ref.size());
    const common::PoseList ref_n(ref.begin(), ref.begin() + static_cast<long>(n));
    const std::vector<double> dist = distances_travelled(ref_n);
    const bool long_run = !dist.empty() && dist.back() >= 800.0;
    KittiMetric m =
        kitti_metric_for_lengths(est, ref, long_run ? kitti_lengths() : kitti_short_lengths());
    m.short_segments = !long_run;
    return m;
}

}  // namespace ltm::eval
