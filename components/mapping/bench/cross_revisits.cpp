#include "mapping/bench/cross_revisits.hpp"

#include <algorithm>
#include <set>

namespace ltm::mapping::bench {

std::vector<RevisitSegment> cross_revisit_segments(const common::PoseList& a,
                                                   const common::PoseList& b, double radius,
                                                   std::size_t join) {
    std::vector<RevisitSegment> out;
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < a.size(); ++i) {
        bool revisit = false;
        for (std::size_t j = 0; j <= i && j < b.size() && !revisit; ++j)
            revisit = (a[i].translation() - b[j].translation()).squaredNorm() <= r2;
        if (!revisit) continue;
        if (!out.empty() && i <= out.back().last + join) {
            out.back().last = i;
        } else {
            out.push_back({i, i, false});
        }
    }
    return out;
}

void mark_closed_by_local_maps(const common::PoseList& a, const common::PoseList& b,
                               const std::vector<std::uint64_t>& a_maps,
                               const std::vector<std::uint64_t>& b_maps, double radius,
                               const std::vector<std::pair<std::size_t, std::size_t>>& loops,
                               std::vector<RevisitSegment>* segments) {
    std::set<std::pair<std::uint64_t, std::uint64_t>> joined;  // (A's map, B's map)
    for (const auto& [fa, fb] : loops) {
        if (fa < a_maps.size() && fb < b_maps.size()) joined.insert({a_maps[fa], b_maps[fb]});
    }
    const double r2 = radius * radius;
    for (RevisitSegment& s : *segments) {
        const std::size_t a_end = std::min(a.size(), a_maps.size());
        const std::size_t b_end = std::min(b.size(), b_maps.size());
        for (std::size_t i = s.first; i <= s.last && i < a_end && !s.closed; ++i) {
            for (std::size_t j = 0; j <= i && j < b_end && !s.closed; ++j) {
                s.closed = (a[i].translation() - b[j].translation()).squaredNorm() <= r2 &&
                           joined.count({a_maps[i], b_maps[j]}) > 0;
            }
        }
    }
}

}  // namespace ltm::mapping::bench
