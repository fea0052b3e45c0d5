#pragma once
// Summary statistics of a list of non-negative errors.
#include <cstddef>
#include <vector>

namespace ltm::eval {

struct ErrorStats {
    double rmse = 0.0, mean = 0.0, median = 0.0, max = 0.0;
    std::size_t n = 0;
};

// All zero for an empty list. The median of an even count is the mean of the two middle values.
ErrorStats summarize(const std::vector<double>& errors);

// Linear-interpolated percentile (p in [0, 100]) of the values; 0 for an empty list.
double percentile(std::vector<double> values, double p);

}  // namespace ltm::eval
