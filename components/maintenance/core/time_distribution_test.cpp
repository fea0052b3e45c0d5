#include "maintenance/core/time_distribution.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ltm::maintenance {
namespace {

TEST(TimeDistribution, TwoInstantsAreTheirDistanceApartAtAnySigma) {
    TimeSamples a, b;
    a.add(2.0);
    b.add(7.5);
    EXPECT_NEAR(wasserstein1(a, b, 0.0), 5.5, 1e-12);
    EXPECT_NEAR(wasserstein1(a, b, 1.0), 5.5, 1e-3);  // smoothing both alike keeps a shift
    EXPECT_NEAR(wasserstein1(a, b, 10.0), 5.5, 1e-3);
}

TEST(TimeDistribution, ShiftedMixturesAreTheShiftApart) {
    // D_b(t) = D_a(t - d): W1 = d exactly (closed form), with or without smoothing.
    TimeSamples a, b;
    const double times[] = {0.0, 0.3, 1.7, 4.0, 4.1, 9.0};
    for (double t : times) {
        a.add(t);
        b.add(t + 2.5);
    }
    EXPECT_NEAR(wasserstein1(a, b, 0.0), 2.5, 1e-9);
    EXPECT_NEAR(wasserstein1(a, b, 0.5), 2.5, 2e-3);
    EXPECT_NEAR(wasserstein1(a, b, 3.0), 2.5, 2e-3);
}

TEST(TimeDistribution, InstantAgainstUniformIsHalfTheSpan) {
    // A voxel seen once at the start of a local map observed uniformly over [0, L]:
    // W1(delta_0, U[0, L]) = L / 2; F_a - F_b never changes sign, so smoothing keeps it.
    const double L = 30.0;
    TimeSamples a, b;
    a.add(0.0);
    for (int k = 0; k <= 300; ++k) b.add(L * k / 300.0);
    EXPECT_NEAR(wasserstein1(a, b, 0.0), L / 2.0, 1e-9);
    EXPECT_NEAR(wasserstein1(a, b, 1.0), L / 2.0, 0.02);
}

TEST(TimeDistribution, IdenticalAndWeightedDistributions) {
    TimeSamples a, b;
    for (int k = 0; k < 10; ++k) {
        a.add(k);
        b.add(k);
    }
    EXPECT_NEAR(wasserstein1(a, b, 1.0), 0.0, 1e-9);
    // Weights: 3 at t=0 and 1 at t=4 against one at t=1: |0 - 1| * 3/4 + |4 - 1| * 1/4 = 1.5.
    TimeSamples c, d;
    c.add(0.0, 3.0);
    c.add(4.0, 1.0);
    d.add(1.0);
    EXPECT_NEAR(wasserstein1(c, d, 0.0), 1.5, 1e-12);
    EXPECT_EQ(wasserstein1(TimeSamples{}, d, 1.0), 0.0);
}

TEST(TimeDistribution, HistogramAgreesWithSamples) {
    SlotHistogram h, v;
    TimeSamples a, b;
    for (int s = 0; s < 40; ++s) {
        add_to_histogram(v, s, 2, 100);
        b.add(s + 0.5, 2.0);
        if (s >= 10 && s < 14) {
            add_to_histogram(h, s, 1, 100);
            a.add(s + 0.5);
        }
    }
    EXPECT_NEAR(histogram_wasserstein1(h, v, 0.0), wasserstein1(a, b, 0.0), 1e-9);
    EXPECT_NEAR(histogram_wasserstein1(h, v, 2.0), wasserstein1(a, b, 2.0), 0.05);
    EXPECT_NEAR(histogram_wasserstein1(v, v, 2.0), 0.0, 1e-9);
}

TEST(TimeDistribution, HistogramStaysBoundedAndKeepsItsMass) {
    SlotHistogram h;
    for (int s = 0; s < 500; ++s) add_to_histogram(h, s * 3, 1, 16);
    EXPECT_EQ(h.size(), 16u);
    EXPECT_EQ(histogram_total(h), 500u);
    double mean = 0.0;  // the mean time is kept (the true one is 3 * 249.5)
    for (const SlotCount& e : h) mean += double(e.slot) * e.count / 500.0;
    EXPECT_NEAR(mean, 3 * 249.5, 3.0);
    EXPECT_GE(h.front().slot, 0);
    EXPECT_LE(h.back().slot, 499 * 3);
    for (std::size_t k = 1; k < h.size(); ++k) EXPECT_LT(h[k - 1].slot, h[k].slot);
    // A history of 2 short visits far apart stays two visits: merging never crosses the gap.
    SlotHistogram visits;
    for (int s = 0; s < 30; ++s) add_to_histogram(visits, s, 1, 8);
    for (int s = 5000; s < 5030; ++s) add_to_histogram(visits, s, 1, 8);
    int early = 0;
    for (const SlotCount& e : visits) early += e.slot < 100 ? e.count : 0;
    EXPECT_EQ(early, 30);
    add_to_histogram(h, 499 * 3, 65535, 16);  // saturates, never wraps
    EXPECT_EQ(h.back().count, 65535);
    EXPECT_EQ(h.back().slot, 499 * 3);
}

}  // namespace
}  // namespace ltm::maintenance
