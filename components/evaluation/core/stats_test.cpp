#include "evaluation/core/stats.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::eval {
namespace {

TEST(Stats, HandComputedSummary) {
    const ErrorStats s = summarize({4.0, 1.0, 3.0, 2.0});
    EXPECT_EQ(s.n, 4u);
    EXPECT_DOUBLE_EQ(s.mean, 2.5);
    EXPECT_DOUBLE_EQ(s.median, 2.5);
    EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4.0));
    EXPECT_DOUBLE_EQ(s.max, 4.0);
    EXPECT_EQ(summarize({}).n, 0u);
}

TEST(Stats, PercentileInterpolates) {
    std::vector<double> v;
    for (int i = 10; i >= 0; --i) v.push_back(i);  // 0..10, unsorted
    EXPECT_DOUBLE_EQ(percentile(v, 90.0), 9.0);
    EXPECT_DOUBLE_EQ(percentile(v, 95.0), 9.5);
    EXPECT_DOUBLE_EQ(percentile(v, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(percentile({}, 50.0), 0.0);
}

}  // namespace
}  // namespace ltm::eval
