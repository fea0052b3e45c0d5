#include "slam/bench/lap_growth.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::slam::bench {
namespace {

// "+3.1 %" of b over a; "-" without a base.
void growth(std::FILE* out, double a, double b) {
    if (a > 0.0 && b >= 0.0) {
        std::fprintf(out, " %+7.1f %%", 100.0 * (b - a) / a);
    } else {
        std::fprintf(out, " %9s", "-");
    }
}

}  // namespace

std::vector<std::size_t> lap_ends(const common::PoseList& ref, std::size_t laps) {
    std::vector<std::size_t> ends;
    if (ref.empty() || laps == 0) return ends;
    const Eigen::Vector3d start = ref[0].translation();
    const Eigen::Vector3d heading = ref[0].linear().col(0);
    std::size_t lap_start = 0;
    std::size_t best = 0;
    double best_d = -1.0;  // < 0: not near the start
    for (std::size_t i = 1; i < ref.size() && ends.size() + 1 < laps; ++i) {
        const double d = (ref[i].translation() - start).norm();
        const bool near = i >= lap_start + 300 && d < 2.0 &&
                          ref[i].linear().col(0).dot(heading) > std::cos(M_PI / 4);
        if (near && (best_d < 0.0 || d < best_d)) {
            best = i;
            best_d = d;
        } else if (!near && best_d >= 0.0) {
            ends.push_back(best - 1);
            lap_start = best;
            best_d = -1.0;
        }
    }
    ends.push_back(ref.size() - 1);
    return ends;
}

double p95(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(0.95 * double(v.size())))];
}

void LapGrowthLog::add(const LapSample& s, std::FILE* out) {
    samples_.push_back(s);
    std::fprintf(
        out,
        "lap %zu (frame %zu): mapper %.1f MiB, disk %.1f MiB, %zu local maps, %zu "
        "keyframes, graph %zu nodes %zu edges, %zu loops; %zu optimisations, p95 %.1f ms\n",
        s.lap, s.frame, s.mapper_mib, s.disk_mib, s.local_maps, s.keyframes, s.nodes, s.edges,
        s.loops, s.optimisations, s.optimise_p95_ms);
    if (s.ate_rmse >= 0.0) {
        std::fprintf(out,
                     "  so far: ATE rmse %.3f m (%.4f %% of the path), revisits %zu/%zu closed, "
                     "longest revisit without a loop %zu frames\n",
                     s.ate_rmse, s.ate_percent, s.revisits_closed, s.revisits, s.longest_unclosed);
    }
    std::fflush(out);
}

void LapGrowthLog::report(std::FILE* out) const {
    if (samples_.size() < 2) return;
    std::fprintf(out,
                 "growth by lap (over the lap before):\n  lap  mapper MiB    growth  disk MiB    "
                 "growth  local maps    growth  keyframes    growth  nodes  edges  opt p95 ms\n");
    for (std::size_t i = 0; i < samples_.size(); ++i) {
        const LapSample& s = samples_[i];
        const LapSample* p = i ? &samples_[i - 1] : nullptr;
        std::fprintf(out, "  %3zu  %10.1f", s.lap, s.mapper_mib);
        growth(out, p ? p->mapper_mib : 0.0, s.mapper_mib);
        std::fprintf(out, "  %8.1f", s.disk_mib);
        growth(out, p ? p->disk_mib : 0.0, s.disk_mib);
        std::fprintf(out, "  %10zu", s.local_maps);
        growth(out, p ? double(p->local_maps) : 0.0, double(s.local_maps));
        std::fprintf(out, "  %9zu", s.keyframes);
        growth(out, p ? double(p->keyframes) : 0.0, double(s.keyframes));
        std::fprintf(out, "  %5zu  %5zu  %10.1f\n", s.nodes, s.edges, s.optimise_p95_ms);
    }
    double worst = 0.0;
    for (std::size_t i = 1; i < samples_.size(); ++i) {
        const double a = samples_[i - 1].mapper_mib, b = samples_[i].mapper_mib;
        if (a > 0.0) worst = std::max(worst, 100.0 * (b - a) / a);
        const double da = samples_[i - 1].disk_mib, db = samples_[i].disk_mib;
        if (da > 0.0 && db >= 0.0) worst = std::max(worst, 100.0 * (db - da) / da);
    }
    std::fprintf(out, "largest growth of memory or disk in a lap after the first: %+.1f %%\n",
                 worst);
}

}  // namespace ltm::slam::bench
