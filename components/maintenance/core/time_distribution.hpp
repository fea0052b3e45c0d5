#pragma once
// Time distributions of observations and their 1-D Wasserstein distance (METHOD.md section 5,
// the paper's Eq. 14):
//   D(t) = (1 / sum w) sum_k w_k Normal(t; t_k, sigma^2),   W1(D_a, D_b) = integral |F_a - F_b| dt
// with F the cumulative distributions. Times are "map time" (see MapClock): seconds of observation,
// with the gaps between sessions shortened.
#include <cstdint>
#include <utility>
#include <vector>

namespace ltm::maintenance {

// Weighted observation times (kernel centres t_k with weights w_k > 0).
struct TimeSamples {
    std::vector<double> times;
    std::vector<double> weights;  // empty: every weight 1

    void add(double t, double w = 1.0);
    bool empty() const { return times.empty(); }
    double total_weight() const;
};

// W1 between the two Gaussian-smoothed distributions (sigma > 0), or between the empirical ones
// (sigma == 0, exact). Smoothed: integrated numerically over the support (step sigma / 16); the
// stretches between clusters of samples more than 12 sigma apart are integrated in closed form.
// 0 when either is empty. Units: those of the times.
double wasserstein1(const TimeSamples& a, const TimeSamples& b, double sigma);

// A histogram on time slots of a fixed width (slot k covers [k w, (k + 1) w)): what a voxel keeps
// of its observations. Sorted by slot, one entry a slot, counts saturate at 65535.
struct SlotCount {
    std::int32_t slot = 0;
    std::uint16_t count = 0;
};
using SlotHistogram = std::vector<SlotCount>;

// Adds n observations in `slot`. When the histogram holds more than `max_entries` slots, the two
// closest neighbouring entries (the oldest of equally close pairs) are merged at their
// count-weighted mean slot until it fits: memory is bounded, and the mass and the mean of the
// distribution are kept (its shape coarsens evenly).
void add_to_histogram(SlotHistogram& h, std::int32_t slot, std::uint16_t n,
                      std::size_t max_entries);
std::uint32_t histogram_total(const SlotHistogram& h);

// W1 of two slot histograms (slot centres as times, counts as weights), smoothed with a Gaussian
// of `sigma_slots` slots (0: empirical), in slots. Exact for sigma_slots == 0; otherwise the
// smoothed CDF difference is sampled at every slot boundary (a discrete convolution), which is
// accurate to a few percent for sigma_slots >= 1.
double histogram_wasserstein1(const SlotHistogram& a, const SlotHistogram& b, double sigma_slots);

}  // namespace ltm::maintenance
