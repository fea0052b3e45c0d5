#include "maintenance/core/time_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ltm::maintenance {

namespace {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

struct Atom {
    double t;
    double c;  // +w/W_a or -w/W_b
};

// The signed atoms of F_a - F_b, sorted by time; empty when either side has no weight.
std::vector<Atom> signed_atoms(const TimeSamples& a, const TimeSamples& b) {
    const double wa = a.total_weight(), wb = b.total_weight();
    std::vector<Atom> atoms;
    if (!(wa > 0.0) || !(wb > 0.0)) return atoms;
    atoms.reserve(a.times.size() + b.times.size());
    for (std::size_t i = 0; i < a.times.size(); ++i)
        atoms.push_back({a.times[i], (a.weights.empty() ? 1.0 : a.weights[i]) / wa});
    for (std::size_t i = 0; i < b.times.size(); ++i)
        atoms.push_back({b.times[i], -(b.weights.empty() ? 1.0 : b.weights[i]) / wb});
    std::sort(atoms.begin(), atoms.end(), [](const Atom& x, const Atom& y) { return x.t < y.t; });
    return atoms;
}

}  // namespace

void TimeSamples::add(double t, double w) {
    if (!weights.empty() || w != 1.0) {
        if (weights.empty()) weights.assign(times.size(), 1.0);
        weights.push_back(w);
    }
    times.push_back(t);
}

double TimeSamples::total_weight() const {
    if (weights.empty()) return double(times.size());
    double s = 0.0;
    for (double w : weights) s += w;
    return s;
}

double wasserstein1(const TimeSamples& a, const TimeSamples& b, double sigma) {
    const std::vector<Atom> atoms = signed_atoms(a, b);
    if (atoms.empty()) return 0.0;
    if (!(sigma > 0.0)) {  // empirical: F_a - F_b is constant between consecutive atoms
        double w = 0.0, g = 0.0;
        for (std::size_t i = 0; i + 1 < atoms.size(); ++i) {
            g += atoms[i].c;
            w += std::abs(g) * (atoms[i + 1].t - atoms[i].t);
        }
        return w;
    }
    // Smoothed: clusters of atoms closer than 12 sigma; F_a - F_b is integrated numerically over
    // each cluster's support (+-6 sigma) and is constant (the running sum) between clusters.
    const double reach = 6.0 * sigma, step = sigma / 16.0;
    double w = 0.0, before = 0.0;  // `before`: the sum of the atoms of earlier clusters
    std::size_t first = 0;
    while (first < atoms.size()) {
        std::size_t last = first;
        while (last + 1 < atoms.size() && atoms[last + 1].t - atoms[last].t <= 2.0 * reach) ++last;
        const double lo = atoms[first].t - reach, hi = atoms[last].t + reach;
        const std::size_t n = std::max<std::size_t>(2, std::size_t(std::ceil((hi - lo) / step)));
        const double h = (hi - lo) / double(n);
        for (std::size_t k = 0; k < n; ++k) {  // midpoint rule
            const double t = lo + (double(k) + 0.5) * h;
            double g = before;
            for (std::size_t j = first; j <= last; ++j)
                g += atoms[j].c * normal_cdf((t - atoms[j].t) / sigma);
            w += std::abs(g) * h;
        }
        for (std::size_t j = first; j <= last; ++j) before += atoms[j].c;
        if (last + 1 < atoms.size()) w += std::abs(before) * ((atoms[last + 1].t - reach) - hi);
        first = last + 1;
    }
    return w;
}

void add_to_histogram(SlotHistogram& h, std::int32_t slot, std::uint16_t n,
                      std::size_t max_entries) {
    if (n == 0) return;
    auto it = std::lower_bound(h.begin(), h.end(), slot,
                               [](const SlotCount& e, std::int32_t s) { return e.slot < s; });
    if (it != h.end() && it->slot == slot) {
        it->count = std::uint16_t(std::min<std::uint32_t>(65535u, std::uint32_t(it->count) + n));
    } else {
        h.insert(it, SlotCount{slot, n});
    }
    max_entries = std::max<std::size_t>(max_entries, 2);
    while (h.size() > max_entries) {
        // The closest neighbours (the oldest of equally close ones) become one entry at their
        // count-weighted mean slot: the distribution keeps its shape and its mass.
        std::size_t k = 0;
        for (std::size_t j = 1; j + 1 < h.size(); ++j)
            if (h[j + 1].slot - h[j].slot < h[k + 1].slot - h[k].slot) k = j;
        const double a = h[k].count, b = h[k + 1].count;
        const double mean = (a * h[k].slot + b * h[k + 1].slot) / std::max(a + b, 1.0);
        h[k].slot = std::int32_t(std::lround(mean));
        h[k].count = std::uint16_t(std::min(65535.0, a + b));
        h.erase(h.begin() + std::ptrdiff_t(k) + 1);
    }
}

std::uint32_t histogram_total(const SlotHistogram& h) {
    std::uint32_t n = 0;
    for (const SlotCount& e : h) n += e.count;
    return n;
}

double histogram_wasserstein1(const SlotHistogram& a, const SlotHistogram& b, double sigma_slots) {
    const double na = histogram_total(a), nb = histogram_total(b);
    if (!(na > 0.0) || !(nb > 0.0)) return 0.0;
    // The signed slot masses of F_a - F_b, merged by slot.
    // Kept per thread (its room reused: called for every voxel a pass judges).
    thread_local std::vector<std::pair<std::int32_t, double>> d;
    d.clear();
    d.reserve(a.size() + b.size());
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (j == b.size() || (i < a.size() && a[i].slot < b[j].slot)) {
            d.emplace_back(a[i].slot, a[i].count / na);
            ++i;
        } else if (i == a.size() || b[j].slot < a[i].slot) {
            d.emplace_back(b[j].slot, -b[j].count / nb);
            ++j;
        } else {
            d.emplace_back(a[i].slot, a[i].count / na - b[j].count / nb);
            ++i;
            ++j;
        }
    }
    if (!(sigma_slots > 0.0)) {  // exact: constant between slot centres
        double w = 0.0, g = 0.0;
        for (std::size_t k = 0; k + 1 < d.size(); ++k) {
            g += d[k].second;
            w += std::abs(g) * double(d[k + 1].first - d[k].first);
        }
        return w;
    }
    // Smoothed: G(x) = sum_k d_k Phi((x - c_k) / sigma) at every slot boundary x (slot centres
    // c_k = slot + 0.5), by clusters of slots closer than 2 K (K = 6 sigma, beyond which Phi is
    // 0 or 1); between clusters G is the running sum.
    const int K = int(std::ceil(6.0 * sigma_slots));
    // Phi((m - 0.5) / sigma), m = -K..K+1, kept per thread for the last sigma (one per map).
    thread_local double table_sigma = -1.0;
    thread_local std::vector<double> phi;
    if (sigma_slots != table_sigma) {
        phi.assign(std::size_t(2 * K + 2), 0.0);
        for (int m = -K; m <= K + 1; ++m)
            phi[std::size_t(m + K)] = normal_cdf((double(m) - 0.5) / sigma_slots);
        table_sigma = sigma_slots;
    }
    double w = 0.0, before = 0.0;
    std::size_t first = 0;
    while (first < d.size()) {
        std::size_t last = first;
        while (last + 1 < d.size() && d[last + 1].first - d[last].first <= 2 * K) ++last;
        const std::int32_t lo = d[first].first - K, hi = d[last].first + K + 1;
        for (std::int32_t x = lo; x <= hi; ++x) {  // boundary x: between slot x - 1 and slot x
            double g = before;
            for (std::size_t k = first; k <= last; ++k) {
                const int m = x - d[k].first;
                if (m < -K) break;
                g += d[k].second * (m > K + 1 ? 1.0 : phi[std::size_t(m + K)]);
            }
            w += std::abs(g);
        }
        for (std::size_t k = first; k <= last; ++k) before += d[k].second;
        if (last + 1 < d.size()) w += std::abs(before) * double((d[last + 1].first - K) - hi - 1);
        first = last + 1;
    }
    return w;
}

}  // namespace ltm::maintenance
