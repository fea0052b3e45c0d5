#include "evaluation/core/place_recognition.hpp"

#include <algorithm>
#include <set>

namespace ltm::eval {
namespace {

// Sorted by x: the frames of `ref` whose x is within radius of a query are a contiguous range,
// which keeps the revisit search near-linear for long trajectories.
struct SortedByX {
    std::vector<std::size_t> order;
    std::vector<double> xs;
    explicit SortedByX(const common::PoseList& ref) : order(ref.size()) {
        for (std::size_t i = 0; i < ref.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return ref[a].translation().x() < ref[b].translation().x();
        });
        for (std::size_t i : order) xs.push_back(ref[i].translation().x());
    }
};

// True when `ref` has a frame j (accepted by `allowed`) within radius of p.
template <typename Allowed>
bool has_revisit(const SortedByX& sorted, const common::PoseList& ref, const Eigen::Vector3d& p,
                 double radius, Allowed allowed) {
    auto it = std::lower_bound(sorted.xs.begin(), sorted.xs.end(), p.x() - radius);
    for (auto k = static_cast<std::size_t>(it - sorted.xs.begin()); k < sorted.xs.size(); ++k) {
        if (sorted.xs[k] > p.x() + radius) break;
        const std::size_t j = sorted.order[k];
        if (allowed(j) && (ref[j].translation() - p).norm() <= radius) return true;
    }
    return false;
}

void finish(PlaceRecognitionResult& r) {
    r.detected = r.true_positives + r.false_positives;
    r.precision = r.detected ? static_cast<double>(r.true_positives) / r.detected : 0.0;
    r.recall =
        r.revisit_queries ? static_cast<double>(r.recalled_queries) / r.revisit_queries : 0.0;
    r.f1 = r.precision + r.recall > 0.0 ? 2.0 * r.precision * r.recall / (r.precision + r.recall)
                                        : 0.0;
}

}  // namespace

PlaceRecognitionResult evaluate_loops(const std::vector<LoopPair>& loops,
                                      const common::PoseList& reference,
                                      const PlaceRecognitionConfig& config) {
    PlaceRecognitionResult r;
    r.correct.assign(loops.size(), false);
    std::set<std::size_t> recalled;
    for (std::size_t k = 0; k < loops.size(); ++k) {
        const std::size_t q = std::max(loops[k].query, loops[k].match);
        const std::size_t m = std::min(loops[k].query, loops[k].match);
        if (q >= reference.size()) {
            ++r.out_of_range;
            continue;
        }
        if (q - m < config.min_frame_gap) {
            ++r.trivial;
            continue;
        }
        const double d = (reference[q].translation() - reference[m].translation()).norm();
        if (d <= config.revisit_radius) {
            ++r.true_positives;
            r.correct[k] = true;
            recalled.insert(q);
        } else {
            ++r.false_positives;
        }
    }
    const SortedByX sorted(reference);
    for (std::size_t q = 0; q < reference.size(); ++q) {
        const bool revisit =
            has_revisit(sorted, reference, reference[q].translation(), config.revisit_radius,
                        [&](std::size_t j) { return j < q && q - j >= config.min_frame_gap; });
        if (revisit) ++r.revisit_queries;
    }
    r.recalled_queries = recalled.size();
    finish(r);
    return r;
}

PlaceRecognitionResult evaluate_cross_session_loops(const std::vector<LoopPair>& loops,
                                                    const common::PoseList& query_reference,
                                                    const common::PoseList& match_reference,
                                                    const PlaceRecognitionConfig& config) {
    PlaceRecognitionResult r;
    r.correct.assign(loops.size(), false);
    std::set<std::size_t> recalled;
    for (std::size_t k = 0; k < loops.size(); ++k) {
        const LoopPair& l = loops[k];
        if (l.query >= query_reference.size() || l.match >= match_reference.size()) {
            ++r.out_of_range;
            continue;
        }
        const double d =
            (query_reference[l.query].translation() - match_reference[l.match].translation())
                .norm();
        if (d <= config.revisit_radius) {
            ++r.true_positives;
            r.correct[k] = true;
            recalled.insert(l.query);
        } else {
            ++r.false_positives;
        }
    }
    const SortedByX sorted(match_reference);
    for (const auto& pose : query_reference)
        if (has_revisit(sorted, match_reference, pose.translation(), config.revisit_radius,
                        [](std::size_t) { return true; }))
            ++r.revisit_queries;
    r.recalled_queries = recalled.size();
    finish(r);
    return r;
}

}  // namespace ltm::eval
