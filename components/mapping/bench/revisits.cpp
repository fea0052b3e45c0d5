#include "mapping/bench/revisits.hpp"

#include <algorithm>

namespace ltm::mapping::bench {

std::vector<RevisitSegment> revisit_segments(const common::PoseList& ref, double radius,
                                             std::size_t min_gap, std::size_t join) {
    std::vector<RevisitSegment> out;
    const double r2 = radius * radius;
    for (std::size_t q = min_gap; q < ref.size(); ++q) {
        bool revisit = false;
        for (std::size_t m = 0; m + min_gap <= q && !revisit; ++m) {
            revisit = (ref[q].translation() - ref[m].translation()).squaredNorm() <= r2;
        }
        if (!revisit) continue;
        if (!out.empty() && q <= out.back().last + join) {
            out.back().last = q;
        } else {
            out.push_back({q, q, false});
        }
    }
    return out;
}

void mark_closed(const std::vector<std::size_t>& queries, std::vector<RevisitSegment>* segments) {
    for (RevisitSegment& s : *segments) {
        for (const std::size_t q : queries) {
            if (q >= s.first && q <= s.last) s.closed = true;
        }
    }
}

std::size_t longest_unclosed_run(const std::vector<RevisitSegment>& segments,
                                 std::vector<std::size_t> queries) {
    std::sort(queries.begin(), queries.end());
    std::size_t longest = 0;
    for (const RevisitSegment& s : segments) {
        std::size_t from = s.first;  // the first frame of the current run
        for (auto q = std::lower_bound(queries.begin(), queries.end(), s.first);
             q != queries.end() && *q <= s.last; ++q) {
            longest = std::max(longest, *q - from);
            from = *q + 1;
        }
        if (from <= s.last) longest = std::max(longest, s.last + 1 - from);
    }
    return longest;
}

}  // namespace ltm::mapping::bench
