#include "places/core/local_features.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace ltm::places {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// Voxel centroids of the finite points within `reach` (horizontally) of `centre`.
std::vector<Eigen::Vector3d> voxel_centroids(const std::vector<Eigen::Vector3f>& points,
                                             const Eigen::Vector3d& centre, double reach,
                                             double voxel) {
    struct Acc {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        int count = 0;
    };
    std::unordered_map<std::uint64_t, std::uint32_t> index;
    index.reserve(points.size() / 4 + 16);
    std::vector<Acc> acc;
    const double reach2 = reach * reach, inv = 1.0 / voxel;
    constexpr std::int64_t kBias = 1 << 20;  // keys: 21 bits an axis
    for (const Eigen::Vector3f& pf : points) {
        if (!pf.allFinite()) continue;
        const Eigen::Vector3d p = pf.cast<double>();
        const double dx = p.x() - centre.x(), dy = p.y() - centre.y();
        if (dx * dx + dy * dy > reach2) continue;
        const std::int64_t ix = std::int64_t(std::floor(dx * inv)) + kBias;
        const std::int64_t iy = std::int64_t(std::floor(dy * inv)) + kBias;
        const std::int64_t iz = std::int64_t(std::floor((p.z() - centre.z()) * inv)) + kBias;
        if (iz < 0 || iz >= 2 * kBias) continue;  // absurd heights
        const std::uint64_t key =
            (std::uint64_t(ix) << 42) | (std::uint64_t(iy) << 21) | std::uint64_t(iz);
        const auto [it, fresh] = index.emplace(key, std::uint32_t(acc.size()));
        if (fresh) acc.emplace_back();
        Acc& a = acc[it->second];
        a.sum += p;
        ++a.count;
    }
    std::vector<Eigen::Vector3d> out;
    out.reserve(acc.size());
    for (const Acc& a : acc) out.push_back(a.sum / a.count);
    return out;
}

// A square 2-D grid of cells around a centre, each listing the voxels whose x, y fall in it.
struct CellGrid {
    double x0 = 0.0, y0 = 0.0, cell = 1.0;
    int n = 0;                         // n x n cells
    std::vector<std::uint32_t> start;  // n * n + 1 offsets into `items`
    std::vector<std::uint32_t> items;  // voxel indices, grouped by cell
    std::vector<float> lowest;         // per cell: the lowest voxel's z (+inf when empty)

    int cx(double x) const { return int(std::floor((x - x0) / cell)); }
    int cy(double y) const { return int(std::floor((y - y0) / cell)); }
    bool inside(int i, int j) const { return i >= 0 && j >= 0 && i < n && j < n; }
    std::size_t at(int i, int j) const { return std::size_t(j) * n + i; }
};

CellGrid make_grid(const std::vector<Eigen::Vector3d>& voxels, const Eigen::Vector3d& centre,
                   double half_extent, double cell) {
    CellGrid g;
    g.cell = cell;
    g.n = std::max(1, int(std::ceil(2.0 * half_extent / cell)));
    g.x0 = centre.x() - 0.5 * g.n * cell;
    g.y0 = centre.y() - 0.5 * g.n * cell;
    const std::size_t cells = std::size_t(g.n) * g.n;
    std::vector<std::uint32_t> which(voxels.size(), std::uint32_t(cells));
    g.start.assign(cells + 1, 0);
    g.lowest.assign(cells, std::numeric_limits<float>::infinity());
    for (std::size_t k = 0; k < voxels.size(); ++k) {
        const int i = g.cx(voxels[k].x()), j = g.cy(voxels[k].y());
        if (!g.inside(i, j)) continue;
        const std::size_t c = g.at(i, j);
        which[k] = std::uint32_t(c);
        ++g.start[c + 1];
        g.lowest[c] = std::min(g.lowest[c], float(voxels[k].z()));
    }
    for (std::size_t c = 0; c < cells; ++c) g.start[c + 1] += g.start[c];
    g.items.resize(g.start[cells]);
    std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
    for (std::size_t k = 0; k < voxels.size(); ++k) {
        if (which[k] < cells) g.items[fill[which[k]]++] = std::uint32_t(k);
    }
    return g;
}

// Per cell: 1 where the lowest voxel is ground (no cell within the window lies lower than the
// slope allows).
std::vector<std::uint8_t> ground_cells(const CellGrid& g, const LocalFeatureConfig& config) {
    const int w = int(std::ceil(config.ground_window / g.cell));
    const double slope = std::tan(config.ground_max_slope_deg * M_PI / 180.0);
    std::vector<std::uint8_t> ground(g.lowest.size(), 0);
    for (int j = 0; j < g.n; ++j) {
        for (int i = 0; i < g.n; ++i) {
            const float z = g.lowest[g.at(i, j)];
            if (!std::isfinite(z)) continue;
            bool ok = true;
            for (int dj = -w; dj <= w && ok; ++dj) {
                for (int di = -w; di <= w; ++di) {
                    if (!g.inside(i + di, j + dj)) continue;
                    const float zn = g.lowest[g.at(i + di, j + dj)];
                    if (!std::isfinite(zn)) continue;
                    const double d = g.cell * std::max(0.0, std::hypot(di, dj) - 1.0);
                    if (z - zn > slope * d + config.ground_tolerance) {
                        ok = false;
                        break;
                    }
                }
            }
            ground[g.at(i, j)] = ok;
        }
    }
    return ground;
}

// The descriptor of the voxels around `sample` (z relative to sample.z()); `count` gets the
// voxels used.
places::ScanContext describe(const std::vector<Eigen::Vector3d>& voxels, const CellGrid& g,
                             const Eigen::Vector3d& sample, const LocalFeatureConfig& config,
                             int* count) {
    const int rings = config.rings, sectors = config.sectors;
    const std::size_t bins = std::size_t(rings) * sectors;
    places::ScanContext sc;
    sc.kind = places::ScanContextKind::kMeanVariance;
    sc.rings = rings;
    sc.sectors = sectors;
    sc.value.assign(bins, 0.0f);
    sc.spread.assign(bins, 0.0f);
    sc.occupied.assign(bins, 0);
    std::vector<double> sum(bins, 0.0), sum_sq(bins, 0.0);
    std::vector<int> n(bins, 0);
    const double r = config.radius, r2 = r * r;
    const double sector_scale = sectors / kTwoPi;
    const int i0 = g.cx(sample.x() - r), i1 = g.cx(sample.x() + r);
    const int j0 = g.cy(sample.y() - r), j1 = g.cy(sample.y() + r);
    *count = 0;
    for (int j = std::max(0, j0); j <= std::min(g.n - 1, j1); ++j) {
        for (int i = std::max(0, i0); i <= std::min(g.n - 1, i1); ++i) {
            const std::size_t c = g.at(i, j);
            for (std::uint32_t k = g.start[c]; k < g.start[c + 1]; ++k) {
                const Eigen::Vector3d& p = voxels[g.items[k]];
                const double dx = p.x() - sample.x(), dy = p.y() - sample.y();
                const double d2 = dx * dx + dy * dy;
                if (d2 >= r2) continue;
                const double z = p.z() - sample.z();
                if (z > config.max_height) continue;
                const int ring =
                    config.equal_area_rings ? int(rings * d2 / r2) : int(rings * std::sqrt(d2) / r);
                double azimuth = std::atan2(dy, dx);
                if (azimuth < 0.0) azimuth += kTwoPi;
                const int sector = std::min(sectors - 1, int(azimuth * sector_scale));
                const std::size_t b = std::size_t(std::min(rings - 1, ring)) * sectors + sector;
                sum[b] += z;
                sum_sq[b] += z * z;
                ++n[b];
                ++*count;
            }
        }
    }
    for (std::size_t b = 0; b < bins; ++b) {
        if (n[b] == 0) continue;
        const double mean = sum[b] / n[b];
        sc.occupied[b] = 1;
        sc.value[b] = float(mean);
        sc.spread[b] = float(std::sqrt(std::max(0.0, sum_sq[b] / n[b] - mean * mean)));
    }
    return sc;
}

LocalFeatures features(const std::vector<Eigen::Vector3f>& points, const LocalFeatureConfig& config,
                       const Eigen::Vector3d& centre, double sample_radius) {
    common::throw_if(validate(config), "local_features");
    LocalFeatures out;
    out.sample_spacing = config.sample_spacing;
    const double reach = sample_radius + config.radius + config.ground_window + config.ground_cell;
    const std::vector<Eigen::Vector3d> voxels =
        voxel_centroids(points, centre, reach, config.voxel_size);
    if (voxels.empty()) return out;
    const CellGrid g = make_grid(voxels, centre, reach, config.ground_cell);
    const std::vector<std::uint8_t> ground = ground_cells(g, config);

    // Lattice points within the sample radius whose cell is ground. Ordered so that the first
    // max_samples are spread evenly: the points of the 8-spacing sub-lattice first, then of the
    // 4-spacing one, the 2-spacing one, the rest; nearest to the centre first within each.
    struct Candidate {
        int level;
        double d2;
        Eigen::Vector3d p;
    };
    const auto level = [](int a, int b) {
        for (int k = 8, l = 0; k > 1; k /= 2, ++l) {
            if (a % k == 0 && b % k == 0) return l;
        }
        return 3;
    };
    std::vector<Candidate> candidates;
    const double s = config.sample_spacing, sr2 = sample_radius * sample_radius;
    const int a0 = int(std::ceil((centre.x() - sample_radius) / s));
    const int a1 = int(std::floor((centre.x() + sample_radius) / s));
    const int b0 = int(std::ceil((centre.y() - sample_radius) / s));
    const int b1 = int(std::floor((centre.y() + sample_radius) / s));
    for (int b = b0; b <= b1; ++b) {
        for (int a = a0; a <= a1; ++a) {
            const double x = a * s, y = b * s;
            const double d2 =
                (x - centre.x()) * (x - centre.x()) + (y - centre.y()) * (y - centre.y());
            if (d2 > sr2) continue;
            const int i = g.cx(x), j = g.cy(y);
            if (!g.inside(i, j) || !ground[g.at(i, j)]) continue;
            // Ground height: the mean lowest voxel of the ground cells of the 3 x 3 block.
            double z = 0.0;
            int used = 0;
            for (int dj = -1; dj <= 1; ++dj) {
                for (int di = -1; di <= 1; ++di) {
                    if (!g.inside(i + di, j + dj) || !ground[g.at(i + di, j + dj)]) continue;
                    z += g.lowest[g.at(i + di, j + dj)];
                    ++used;
                }
            }
            candidates.push_back({level(a, b), d2, Eigen::Vector3d(x, y, z / used)});
        }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& l, const Candidate& r) {
                         return l.level != r.level ? l.level < r.level : l.d2 < r.d2;
                     });
    for (const Candidate& c : candidates) {
        if (int(out.size()) >= config.max_samples) break;
        int count = 0;
        places::ScanContext sc = describe(voxels, g, c.p, config, &count);
        if (count < config.min_points_per_descriptor) continue;
        int occupied = 0;
        for (const std::uint8_t o : sc.occupied) occupied += o;
        if (occupied < config.min_occupied_bins) continue;
        out.positions.push_back(c.p);
        out.descriptors.push_back(std::move(sc));
    }
    return out;
}

}  // namespace

std::optional<common::ConfigProblem> validate(const LocalFeatureConfig& config) {
    LocalFeatureConfig c = config;
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

LocalFeatures make_local_features(const std::vector<Eigen::Vector3f>& points,
                                  const LocalFeatureConfig& config) {
    return features(points, config, Eigen::Vector3d::Zero(), config.max_range);
}

LocalFeatures make_local_features(const std::vector<Eigen::Vector3f>& points,
                                  const LocalFeatureConfig& config, const Eigen::Vector3d& centre,
                                  double sample_radius) {
    if (!centre.allFinite() || !(sample_radius > 0.0) || !std::isfinite(sample_radius)) {
        throw common::ConfigError("sample_radius", "must be > 0 around a finite centre");
    }
    return features(points, config, centre, sample_radius);
}

}  // namespace ltm::places
