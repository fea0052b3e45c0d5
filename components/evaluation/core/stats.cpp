#include "evaluation/core/stats.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::eval {

ErrorStats summarize(const std::vector<double>& errors) {
    ErrorStats s;
    s.n = errors.size();
    if (errors.empty()) return s;
    double sum = 0.0, sum_sq = 0.0;
    for (double e : errors) {
        sum += e;
        sum_sq += e * e;
        s.max = std::max(s.max, e);
    }
    s.mean = sum / static_cast<double>(s.n);
    s.rmse = std::sqrt(sum_sq / static_cast<double>(s.n));
    s.median = percentile(errors, 50.0);
    return s;
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double pos = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    const double frac = pos - static_cast<double>(lo);
    return values[lo] + frac * (values[hi] - values[lo]);
}

}  // namespace ltm::eval
