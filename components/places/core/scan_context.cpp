#include "places/core/scan_context.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ltm::places {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

int wrap(int i, int n) { return ((i % n) + n) % n; }

// Column norms of a max-height descriptor, for the cosine distance.
std::vector<float> column_norms(const ScanContext& sc) {
    std::vector<float> n(std::size_t(sc.sectors), 0.0f);
    for (int r = 0; r < sc.rings; ++r) {
        for (int s = 0; s < sc.sectors; ++s) n[std::size_t(s)] += sc.at(r, s) * sc.at(r, s);
    }
    for (float& v : n) v = std::sqrt(v);
    return n;
}

double cosine_distance(const ScanContext& q, const ScanContext& c, int shift,
                       const std::vector<float>& qn, const std::vector<float>& cn) {
    double sum = 0.0;
    int used = 0;
    for (int j = 0; j < q.sectors; ++j) {
        const int k = wrap(j + shift, q.sectors);
        if (qn[std::size_t(j)] <= 0.0f || cn[std::size_t(k)] <= 0.0f) continue;
        double dot = 0.0;
        for (int r = 0; r < q.rings; ++r) dot += double(q.at(r, j)) * c.at(r, k);
        sum += 1.0 - dot / (double(qn[std::size_t(j)]) * cn[std::size_t(k)]);
        ++used;
    }
    return used ? sum / used : 1.0;
}

double gaussian_distance(const ScanContext& q, const ScanContext& c, int shift, double empty_cost) {
    double sum = 0.0;
    int used = 0;
    for (int r = 0; r < q.rings; ++r) {
        for (int j = 0; j < q.sectors; ++j) {
            const std::size_t a = std::size_t(r) * q.sectors + j;
            const std::size_t b = std::size_t(r) * q.sectors + wrap(j + shift, q.sectors);
            const bool oa = q.occupied[a], ob = c.occupied[b];
            if (!oa && !ob) continue;
            ++used;
            if (oa != ob) {
                sum += empty_cost;
                continue;
            }
            const double dm = double(q.value[a]) - c.value[b];
            const double ds = double(q.spread[a]) - c.spread[b];
            sum += std::min(dm * dm + ds * ds, empty_cost);
        }
    }
    return used ? sum / used : empty_cost;
}

bool comparable(const ScanContext& q, const ScanContext& c) {
    return !q.empty() && q.kind == c.kind && q.rings == c.rings && q.sectors == c.sectors &&
           q.value.size() == c.value.size();
}

}  // namespace

std::optional<common::ConfigProblem> validate(const ScanContextConfig& config) {
    ScanContextConfig c = config;  // visit_fields takes a mutable config (loaders write through it)
    common::ConfigChecker k;
    visit_fields(c, "", k);
    k.require(c.min_range < c.max_range, "min_range", "must be smaller than max_range");
    k.require(c.kind == ScanContextKind::kMaxHeight || c.kind == ScanContextKind::kMeanVariance,
              "kind", "is unknown");
    return k.problem();
}

ScanContext make_scan_context(const std::vector<Eigen::Vector3f>& points,
                              const ScanContextConfig& config) {
    ScanContext sc;
    sc.kind = config.kind;
    sc.rings = config.rings;
    sc.sectors = config.sectors;
    const std::size_t bins = std::size_t(sc.rings) * sc.sectors;
    sc.value.assign(bins, 0.0f);
    sc.occupied.assign(bins, 0);
    const bool gaussian = config.kind == ScanContextKind::kMeanVariance;
    std::vector<double> sum, sum_sq;
    std::vector<std::uint32_t> count;
    std::vector<float> max_z;
    if (gaussian) {
        sum.assign(bins, 0.0);
        sum_sq.assign(bins, 0.0);
        count.assign(bins, 0);
    } else {
        max_z.assign(bins, -std::numeric_limits<float>::infinity());
    }
    const double ring_width = config.max_range / config.rings;
    const double sector_width = kTwoPi / config.sectors;
    for (const Eigen::Vector3f& p : points) {
        if (!p.allFinite()) continue;
        const double range = std::hypot(double(p.x()), double(p.y()));
        if (range < config.min_range || range >= config.max_range) continue;
        double azimuth = std::atan2(double(p.y()), double(p.x()));
        if (azimuth < 0.0) azimuth += kTwoPi;
        const int r = std::min(config.rings - 1, int(range / ring_width));
        const int s = std::min(config.sectors - 1, int(azimuth / sector_width));
        const std::size_t b = std::size_t(r) * sc.sectors + s;
        const double z = double(p.z()) + config.sensor_height;
        sc.occupied[b] = 1;
        if (gaussian) {
            sum[b] += z;
            sum_sq[b] += z * z;
            ++count[b];
        } else {
            max_z[b] = std::max(max_z[b], float(z));
        }
    }
    if (gaussian) sc.spread.assign(bins, 0.0f);
    for (std::size_t b = 0; b < bins; ++b) {
        if (!sc.occupied[b]) continue;
        if (gaussian) {
            const double mean = sum[b] / count[b];
            sc.value[b] = float(mean);
            sc.spread[b] = float(std::sqrt(std::max(0.0, sum_sq[b] / count[b] - mean * mean)));
        } else {
            sc.value[b] = std::max(0.0f, max_z[b]);  // as the paper: empty and sub-ground bins 0
        }
    }
    return sc;
}

Eigen::VectorXf ring_key(const ScanContext& sc) {
    Eigen::VectorXf k = Eigen::VectorXf::Zero(sc.rings);
    if (sc.empty()) return k;
    for (int r = 0; r < sc.rings; ++r) {
        double s = 0.0;
        for (int j = 0; j < sc.sectors; ++j) s += sc.at(r, j);
        k[r] = float(s / sc.sectors);
    }
    return k;
}

Eigen::VectorXf sector_key(const ScanContext& sc) {
    Eigen::VectorXf k = Eigen::VectorXf::Zero(sc.sectors);
    if (sc.empty()) return k;
    for (int j = 0; j < sc.sectors; ++j) {
        double s = 0.0;
        for (int r = 0; r < sc.rings; ++r) s += sc.at(r, j);
        k[j] = float(s / sc.rings);
    }
    return k;
}

double distance_at_shift(const ScanContext& query, const ScanContext& candidate, int shift,
                         const ScanContextConfig& config) {
    if (!comparable(query, candidate)) return std::numeric_limits<double>::infinity();
    shift = wrap(shift, query.sectors);
    if (query.kind == ScanContextKind::kMeanVariance) {
        return gaussian_distance(query, candidate, shift, config.empty_bin_cost);
    }
    return cosine_distance(query, candidate, shift, column_norms(query), column_norms(candidate));
}

ScanContextMatch compare(const ScanContext& query, const ScanContext& candidate,
                         const ScanContextConfig& config) {
    const int shift_search_radius = config.shift_search_radius;
    ScanContextMatch best;
    if (!comparable(query, candidate)) return best;
    const int n = query.sectors;
    // The shifts to try: all, or a window around the best sector-key alignment.
    int centre = 0, radius = n;
    if (shift_search_radius > 0 && 2 * shift_search_radius + 1 < n) {
        const Eigen::VectorXf a = sector_key(query), b = sector_key(candidate);
        double best_key = std::numeric_limits<double>::infinity();
        for (int s = 0; s < n; ++s) {
            double d = 0.0;
            for (int j = 0; j < n; ++j) {
                const double x = double(a[j]) - b[wrap(j + s, n)];
                d += x * x;
            }
            if (d < best_key) {
                best_key = d;
                centre = s;
            }
        }
        radius = shift_search_radius;
    }
    std::vector<float> qn, cn;
    const bool gaussian = query.kind == ScanContextKind::kMeanVariance;
    if (!gaussian) {
        qn = column_norms(query);
        cn = column_norms(candidate);
    }
    best.distance = std::numeric_limits<double>::infinity();
    const int first = radius >= n ? 0 : centre - radius;
    const int last = radius >= n ? n - 1 : centre + radius;
    for (int s = first; s <= last; ++s) {
        const int shift = wrap(s, n);
        const double d = gaussian
                             ? gaussian_distance(query, candidate, shift, config.empty_bin_cost)
                             : cosine_distance(query, candidate, shift, qn, cn);
        if (d < best.distance) {
            best.distance = d;
            best.shift = shift;
        }
    }
    best.valid = true;
    double yaw = best.shift * kTwoPi / n;
    if (yaw > M_PI) yaw -= kTwoPi;
    best.yaw = yaw;
    return best;
}

}  // namespace ltm::places
