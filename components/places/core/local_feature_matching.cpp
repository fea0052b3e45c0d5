#include "places/core/local_feature_matching.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace ltm::places {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// Descriptors packed sector-major (index sector * rings + ring) for the shift loop; targets hold
// their sectors twice so that every shift reads one contiguous run. An empty bin holds a far
// sentinel mean (+kFar in queries, -kFar in targets) so that any pair with an empty side costs
// exactly the cap in the unmasked sum (see distance_at).
constexpr float kFar = 1.0e3f;

struct Packed {
    int rings = 0, sectors = 0, copies = 1;
    std::vector<float> mean, spread, occupied;  // per descriptor: copies * sectors * rings
    std::vector<float> count;                   // per descriptor: occupied bins
    std::vector<std::uint8_t> usable;
    std::vector<float> keys;  // per descriptor: 2 * rings

    std::size_t stride() const { return std::size_t(copies) * sectors * rings; }
};

Packed pack(const LocalFeatures& f, int rings, int sectors, int copies, float sentinel) {
    Packed p;
    p.rings = rings;
    p.sectors = sectors;
    p.copies = copies;
    const std::size_t n = f.descriptors.size(), stride = p.stride();
    p.mean.assign(n * stride, sentinel);
    p.spread.assign(n * stride, 0.0f);
    p.occupied.assign(n * stride, 0.0f);
    p.count.assign(n, 0.0f);
    p.usable.assign(n, 0);
    p.keys.assign(n * 2 * rings, 0.0f);
    for (std::size_t k = 0; k < n; ++k) {
        const places::ScanContext& sc = f.descriptors[k];
        const std::size_t bins = std::size_t(rings) * sectors;
        if (sc.kind != places::ScanContextKind::kMeanVariance || sc.rings != rings ||
            sc.sectors != sectors || sc.value.size() != bins || sc.spread.size() != bins ||
            sc.occupied.size() != bins) {
            continue;
        }
        p.usable[k] = 1;
        for (const std::uint8_t o : sc.occupied) p.count[k] += o ? 1.0f : 0.0f;
        for (int c = 0; c < copies; ++c) {
            for (int s = 0; s < sectors; ++s) {
                for (int r = 0; r < rings; ++r) {
                    const std::size_t from = std::size_t(r) * sectors + s;
                    if (!sc.occupied[from]) continue;
                    const std::size_t to = k * stride + (std::size_t(c) * sectors + s) * rings + r;
                    p.mean[to] = sc.value[from];
                    p.spread[to] = sc.spread[from];
                    p.occupied[to] = 1.0f;
                }
            }
        }
        const Eigen::VectorXf key = local_ring_key(sc);
        std::copy(key.data(), key.data() + key.size(), p.keys.begin() + k * 2 * rings);
    }
    return p;
}

// Distance of query q to target t at a shift (query sector j against target sector j + shift).
// With B the bins occupied in both, Nq and Nt those occupied in the query and in the target
// (shift-invariant), and the sentinels making min(d, cap) = cap wherever a side is empty:
//   sum = sum_all (min(d, cap) - cap) + Nq * cap + Nt * unseen - |B| * unseen,
//   used = Nq + Nt - |B|;
// the loop needs only sum_all min(d, cap) and |B|.
inline float distance_at(const Packed& q, std::size_t qi, const Packed& t, std::size_t ti,
                         int shift, float empty_cost, float unseen_cost) {
    const std::size_t n = std::size_t(q.sectors) * q.rings;
    const float* qm = q.mean.data() + qi * q.stride();
    const float* qs = q.spread.data() + qi * q.stride();
    const float* qo = q.occupied.data() + qi * q.stride();
    const std::size_t off = ti * t.stride() + std::size_t(shift) * t.rings;
    const float* tm = t.mean.data() + off;
    const float* ts = t.spread.data() + off;
    const float* to = t.occupied.data() + off;
    // Four-float vectors (GCC/Clang vector extensions: SSE, NEON or plain code alike).
    typedef float V4 __attribute__((vector_size(16)));
    const auto load = [](const float* p) {
        V4 v;
        std::memcpy(&v, p, sizeof v);
        return v;
    };
    const V4 cap = {empty_cost, empty_cost, empty_cost, empty_cost};
    V4 capped[2] = {{0, 0, 0, 0}, {0, 0, 0, 0}}, both[2] = {{0, 0, 0, 0}, {0, 0, 0, 0}};
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {  // two chains of sums: the additions overlap
        for (std::size_t h = 0; h < 2; ++h) {
            const std::size_t k = i + 4 * h;
            const V4 dm = load(qm + k) - load(tm + k), ds = load(qs + k) - load(ts + k);
            const V4 d = dm * dm + ds * ds;
            capped[h] += d < cap ? d : cap;
            both[h] += load(qo + k) * load(to + k);
        }
    }
    const V4 c = capped[0] + capped[1], b = both[0] + both[1];
    float sum_capped = c[0] + c[1] + c[2] + c[3];
    float shared = b[0] + b[1] + b[2] + b[3];
    for (; i < n; ++i) {
        const float dm = qm[i] - tm[i], ds = qs[i] - ts[i];
        sum_capped += std::min(dm * dm + ds * ds, empty_cost);
        shared += qo[i] * to[i];
    }
    const float nq = q.count[qi], nt = t.count[ti];
    const float used = nq + nt - shared;
    if (used <= 0.0f) return empty_cost;
    const float sum = sum_capped - float(n) * empty_cost + nq * empty_cost + nt * unseen_cost -
                      shared * unseen_cost;
    return std::max(0.0f, sum) / used;
}

}  // namespace

std::optional<common::ConfigProblem> validate(const LocalFeatureMatchConfig& config) {
    LocalFeatureMatchConfig c = config;
    common::ConfigChecker k;
    visit_fields(c, "", k);
    return k.problem();
}

Eigen::VectorXf local_ring_key(const places::ScanContext& sc) {
    Eigen::VectorXf key = Eigen::VectorXf::Zero(2 * sc.rings);
    if (sc.empty() || sc.spread.size() != sc.value.size()) return key;
    for (int r = 0; r < sc.rings; ++r) {
        double m = 0.0, s = 0.0;
        int n = 0;
        for (int j = 0; j < sc.sectors; ++j) {
            const std::size_t b = std::size_t(r) * sc.sectors + j;
            if (!sc.occupied[b]) continue;
            m += sc.value[b];
            s += sc.spread[b];
            ++n;
        }
        if (n == 0) continue;
        key[2 * r] = float(m / n);
        key[2 * r + 1] = float(s / n);
    }
    return key;
}

std::vector<FeatureMatch> match_local_features(const LocalFeatures& query,
                                               const LocalFeatures& target,
                                               const LocalFeatureMatchConfig& config) {
    common::throw_if(validate(config), "local_feature_match");
    std::vector<FeatureMatch> out;
    if (query.descriptors.empty() || target.descriptors.empty()) return out;
    const int rings = query.descriptors.front().rings, sectors = query.descriptors.front().sectors;
    if (rings <= 0 || sectors <= 0) return out;
    const Packed q = pack(query, rings, sectors, 1, kFar);
    const Packed t = pack(target, rings, sectors, 2, -kFar);
    const std::size_t nq = query.descriptors.size(), nt = target.descriptors.size();
    const std::size_t key_dim = std::size_t(2 * rings);
    const float empty_cost = float(config.empty_bin_cost);
    const float unseen_cost = float(config.unseen_bin_cost);
    std::vector<std::uint32_t> usable_targets;
    for (std::size_t k = 0; k < nt; ++k) {
        if (t.usable[k]) usable_targets.push_back(std::uint32_t(k));
    }
    const std::size_t candidates =
        std::min(usable_targets.size(), std::size_t(config.key_candidates));
    std::vector<std::pair<float, std::uint32_t>> by_key(usable_targets.size());
    std::vector<float> per_shift(static_cast<std::size_t>(sectors));

    // The target samples by lattice cell, for the sub-lattice refinement.
    const double spacing = target.sample_spacing;
    std::unordered_map<std::uint64_t, std::uint32_t> lattice;
    const auto cell_key = [](long long i, long long j) {
        return (std::uint64_t(std::uint32_t(i)) << 32) | std::uint32_t(j);
    };
    if (spacing > 0.0) {
        for (const std::uint32_t k : usable_targets) {
            const Eigen::Vector3d& p = target.positions[k];
            lattice.emplace(cell_key(std::llround(p.x() / spacing), std::llround(p.y() / spacing)),
                            k);
        }
    }
    const auto refine = [&](std::size_t a, std::size_t b, int shift, double d0) {
        Eigen::Vector3d p = target.positions[b];
        if (lattice.empty()) return p;
        const long long i = std::llround(p.x() / spacing), j = std::llround(p.y() / spacing);
        // A quadratic surface through the 3 x 3 lattice block when all of it is there.
        Eigen::Matrix<double, 9, 6> A;
        Eigen::Matrix<double, 9, 1> y;
        int filled = 0;
        double zs[3][3] = {};
        for (int dj = -1; dj <= 1; ++dj) {
            for (int di = -1; di <= 1; ++di) {
                const auto it = lattice.find(cell_key(i + di, j + dj));
                if (it == lattice.end()) continue;
                const double d = (di == 0 && dj == 0) ? d0
                                                      : distance_at(q, a, t, it->second, shift,
                                                                    empty_cost, unseen_cost);
                A.row(filled) << 1.0, di, dj, di * di, di * dj, dj * dj;
                y[filled] = d;
                zs[dj + 1][di + 1] = target.positions[it->second].z();
                ++filled;
            }
        }
        Eigen::Vector3d moved = p;
        if (filled == 9) {
            const Eigen::Matrix<double, 6, 1> c = A.colPivHouseholderQr().solve(y);
            Eigen::Matrix2d H;
            H << 2.0 * c[3], c[4], c[4], 2.0 * c[5];
            const Eigen::Vector2d g(c[1], c[2]);
            if (H.determinant() > 0.0 && H(0, 0) > 0.0) {
                Eigen::Vector2d off = -H.inverse() * g;
                off = off.cwiseMax(-0.5).cwiseMin(0.5);
                moved.x() += off.x() * spacing;
                moved.y() += off.y() * spacing;
                moved.z() +=
                    0.5 * off.x() * (zs[1][2] - zs[1][0]) + 0.5 * off.y() * (zs[2][1] - zs[0][1]);
                return moved;
            }
        }
        for (int axis = 0; axis < 2; ++axis) {
            const auto lo = lattice.find(axis == 0 ? cell_key(i - 1, j) : cell_key(i, j - 1));
            const auto hi = lattice.find(axis == 0 ? cell_key(i + 1, j) : cell_key(i, j + 1));
            if (lo == lattice.end() || hi == lattice.end()) continue;
            const double dm = distance_at(q, a, t, lo->second, shift, empty_cost, unseen_cost);
            const double dp = distance_at(q, a, t, hi->second, shift, empty_cost, unseen_cost);
            const double curvature = dm - 2.0 * d0 + dp;
            if (!(curvature > 0.0)) continue;
            const double offset = std::clamp(0.5 * (dm - dp) / curvature, -0.5, 0.5);
            moved[axis] += offset * spacing;
            const double dz = target.positions[hi->second].z() - target.positions[lo->second].z();
            moved.z() += 0.5 * offset * dz;
        }
        return moved;
    };
    std::vector<FeatureMatch> mine;
    for (std::size_t a = 0; a < nq; ++a) {
        if (!q.usable[a] || candidates == 0) continue;
        const float* qk = q.keys.data() + a * key_dim;
        for (std::size_t k = 0; k < usable_targets.size(); ++k) {
            const float* tk = t.keys.data() + std::size_t(usable_targets[k]) * key_dim;
            float d = 0.0f;
            for (std::size_t i = 0; i < key_dim; ++i) d += (qk[i] - tk[i]) * (qk[i] - tk[i]);
            by_key[k] = {d, usable_targets[k]};
        }
        std::partial_sort(by_key.begin(), by_key.begin() + std::ptrdiff_t(candidates),
                          by_key.end());
        mine.clear();
        for (std::size_t c = 0; c < candidates; ++c) {
            const std::size_t b = by_key[c].second;
            int best = 0;
            for (int s = 0; s < sectors; ++s) {
                per_shift[std::size_t(s)] = distance_at(q, a, t, b, s, empty_cost, unseen_cost);
                if (per_shift[std::size_t(s)] < per_shift[std::size_t(best)]) best = s;
            }
            const double d0 = per_shift[std::size_t(best)];
            if (d0 > config.max_distance) continue;
            const double dm = per_shift[std::size_t((best + sectors - 1) % sectors)];
            const double dp = per_shift[std::size_t((best + 1) % sectors)];
            const double curvature = dm - 2.0 * d0 + dp;
            const double offset =
                curvature > 0.0 ? std::clamp(0.5 * (dm - dp) / curvature, -0.5, 0.5) : 0.0;
            double yaw = (best + offset) * kTwoPi / sectors;
            while (yaw > M_PI) yaw -= kTwoPi;
            while (yaw <= -M_PI) yaw += kTwoPi;
            mine.push_back({a, b, d0, yaw, Eigen::Vector3d::Constant(double(best))});
        }
        const std::size_t keep = std::min(mine.size(), std::size_t(config.per_query));
        std::partial_sort(
            mine.begin(), mine.begin() + std::ptrdiff_t(keep), mine.end(),
            [](const FeatureMatch& l, const FeatureMatch& r) { return l.distance < r.distance; });
        for (std::size_t k = 0; k < keep; ++k) {
            if (mine[k].distance > config.ratio * mine[0].distance) break;
            FeatureMatch m = mine[k];
            m.target_position = refine(m.query, m.target, int(m.target_position.x()), m.distance);
            out.push_back(m);
        }
    }
    if (config.mutual) {
        // A target's best query among the pairs kept.
        std::vector<double> best(nt, std::numeric_limits<double>::infinity());
        std::vector<std::size_t> who(nt, nq);
        for (const FeatureMatch& m : out) {
            if (m.distance < best[m.target]) {
                best[m.target] = m.distance;
                who[m.target] = m.query;
            }
        }
        out.erase(std::remove_if(out.begin(), out.end(),
                                 [&](const FeatureMatch& m) { return who[m.target] != m.query; }),
                  out.end());
    }
    std::stable_sort(out.begin(), out.end(), [](const FeatureMatch& l, const FeatureMatch& r) {
        return l.distance < r.distance;
    });
    return out;
}

}  // namespace ltm::places
