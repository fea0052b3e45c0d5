#include "mapping/bench/cross_revisits.hpp"

#include <algorithm>

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

}  // namespace ltm::mapping::bench
