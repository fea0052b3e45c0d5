#include "mapping/core/local_map_merge.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace ltm::mapping {
namespace {

struct CellHash {
    std::size_t operator()(const Eigen::Vector3i& c) const {
        std::uint64_t h = 1469598103934665603ull;
        for (int k = 0; k < 3; ++k) {
            h ^= std::uint64_t(std::uint32_t(c[k]));
            h *= 1099511628211ull;
        }
        return std::size_t(h);
    }
};

std::uint32_t saturating_add(std::uint32_t a, std::uint32_t b) {
    return b > std::numeric_limits<std::uint32_t>::max() - a
               ? std::numeric_limits<std::uint32_t>::max()
               : a + b;
}

// The sorted union of two voxels' seen indices, into `into`.
void add_seen(std::vector<std::uint16_t>& into, const std::vector<std::uint16_t>& more) {
    std::vector<std::uint16_t> seen;
    seen.reserve(into.size() + more.size());
    std::set_union(into.begin(), into.end(), more.begin(), more.end(), std::back_inserter(seen));
    into = std::move(seen);
}

// b folded into a (both in the same cell of the same grid frame; seen already remapped).
void merge_voxel(common::VoxelData& a, const common::VoxelData& b) {
    const double wa = double(std::max<std::uint32_t>(a.point_count, 1));
    const double wb = double(std::max<std::uint32_t>(b.point_count, 1));
    const double w = wa + wb;
    a.centre = ((wa * a.centre.cast<double>() + wb * b.centre.cast<double>()) / w).cast<float>();
    const bool na = a.normal.squaredNorm() > 0.0f, nb = b.normal.squaredNorm() > 0.0f;
    if (!na && nb) {
        a.normal = b.normal;
    } else if (na && nb) {
        Eigen::Vector3d n_b = b.normal.cast<double>();
        if (a.normal.dot(b.normal) < 0.0f) n_b = -n_b;
        const Eigen::Vector3d mean = wa * a.normal.cast<double>() + wb * n_b;
        if (mean.norm() > 1e-6 * w) {
            a.normal = mean.normalized().cast<float>();
        } else if (wb > wa) {
            a.normal = b.normal;
        }
    }
    a.planarity = float((wa * a.planarity + wb * b.planarity) / w);
    a.stability = float((wa * a.stability + wb * b.stability) / w);
    a.point_count = saturating_add(a.point_count, b.point_count);
    const double oa = double(std::max<std::uint32_t>(a.life.observations, 1));
    const double ob = double(std::max<std::uint32_t>(b.life.observations, 1));
    a.life.health = float((oa * a.life.health + ob * b.life.health) / (oa + ob));
    a.life.created = std::min(a.life.created, b.life.created);
    a.life.last_seen = std::max(a.life.last_seen, b.life.last_seen);
    a.life.observations = saturating_add(a.life.observations, b.life.observations);
    add_seen(a.life.seen, b.life.seen);
}

// seen indices through `map` (old index -> new index), sorted, without repeats.
void remap_seen(std::vector<std::uint16_t>* seen, const std::vector<std::uint32_t>& map) {
    std::vector<std::uint16_t> out;
    out.reserve(seen->size());
    for (const std::uint16_t s : *seen) {
        if (s < map.size()) out.push_back(std::uint16_t(map[s]));
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    *seen = std::move(out);
}

// The voxel of `into` (out[0, n_into)) whose surface patch a voxel landing in a fresh cell lies
// on (see same_surface in the header), or -1: a neighbouring cell's voxel with a normal, the
// fresh voxel's centre within tol of its plane, its normal (if any) within 30 deg of it, and the
// centre's foot on the plane inside that cell (widened by a tenth of an edge); the nearest plane.
// With foot_in_cell false, any neighbouring cell's voxel whose plane the centre is within tol of
// (the beside_surface rule: the same surface one cell beyond the old patch).
long same_surface_voxel(const std::vector<common::VoxelData>& out, std::size_t n_into,
                        const std::unordered_map<Eigen::Vector3i, std::size_t, CellHash>& cell,
                        const common::VoxelData& v, double g, double tol,
                        bool foot_in_cell = true) {
    long best = -1;
    double best_d = tol;
    const Eigen::Vector3d c = v.centre.cast<double>();
    const bool has_normal = v.normal.squaredNorm() > 0.0f;
    for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dz = -1; dz <= 1; ++dz) {
                if (dx == 0 && dy == 0 && dz == 0) continue;
                const auto it = cell.find(v.index + Eigen::Vector3i(dx, dy, dz));
                if (it == cell.end() || it->second >= n_into) continue;
                const common::VoxelData& w = out[it->second];
                if (w.normal.squaredNorm() == 0.0f) continue;
                if (has_normal && std::abs(w.normal.dot(v.normal)) < 0.866f) continue;
                const Eigen::Vector3d n = w.normal.cast<double>();
                const double d = n.dot(c - w.centre.cast<double>());
                if (std::abs(d) > best_d) continue;
                if (!foot_in_cell) {
                    best_d = std::abs(d);
                    best = long(it->second);
                    continue;
                }
                const Eigen::Vector3d foot = c - d * n;
                const Eigen::Vector3d lo = w.index.cast<double>() * g;
                const double margin = 0.1 * g;
                if (((foot - lo).array() < -margin).any() ||
                    ((lo.array() + g + margin - foot.array()) < 0.0).any())
                    continue;
                best_d = std::abs(d);
                best = long(it->second);
            }
        }
    }
    return best;
}

// Whether `index` lies between voxels of `into` (out[0, n_into)): both cells of some opposite pair
// of its 26 neighbours hold one. Such an empty cell is a hole in an old surface (a cell
// maintenance emptied, or one an earlier day's sparse returns missed), not its edge: the
// beside_surface rule leaves it to be filled.
bool inside_old_voxels(const std::unordered_map<Eigen::Vector3i, std::size_t, CellHash>& cell,
                       std::size_t n_into, const Eigen::Vector3i& index) {
    const auto old = [&](const Eigen::Vector3i& c) {
        const auto it = cell.find(c);
        return it != cell.end() && it->second < n_into;
    };
    for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dz = -1; dz <= 1; ++dz) {
                const Eigen::Vector3i d(dx, dy, dz);
                // Each opposite pair once: the first nonzero component positive.
                const int first = dx != 0 ? dx : (dy != 0 ? dy : dz);
                if (first <= 0) continue;
                if (old(index + d) && old(index - d)) return true;
            }
        }
    }
    return false;
}

}  // namespace

std::vector<std::uint32_t> bound_observation_times(const std::vector<double>& times,
                                                   std::size_t max_times,
                                                   std::vector<double>* kept) {
    const std::size_t n = times.size();
    max_times = std::max<std::size_t>(max_times, 2);
    std::vector<std::uint32_t> index(n);
    kept->clear();
    if (n <= max_times) {
        *kept = times;
        for (std::size_t i = 0; i < n; ++i) index[i] = std::uint32_t(i);
        return index;
    }
    const std::size_t recent = max_times / 2;  // newest, all kept
    const std::size_t old_kept = max_times - recent;
    const std::size_t old = n - recent;  // > old_kept
    std::vector<std::size_t> picks;      // input indices kept, ascending
    picks.reserve(max_times);
    for (std::size_t k = 0; k < old_kept; ++k) {
        // Even steps over [0, old - 1], first and last included.
        picks.push_back(old_kept == 1 ? 0
                                      : std::size_t(std::llround(double(k) * double(old - 1) /
                                                                 double(old_kept - 1))));
    }
    for (std::size_t i = old; i < n; ++i) picks.push_back(i);
    for (const std::size_t p : picks) kept->push_back(times[p]);
    // Each input stamp: the kept one nearest in time (the earlier one on a tie).
    std::size_t j = 0;
    for (std::size_t i = 0; i < n; ++i) {
        while (j + 1 < picks.size() && picks[j + 1] <= i) ++j;
        std::size_t best = j;
        if (picks[j] < i && j + 1 < picks.size() &&
            times[picks[j + 1]] - times[i] < times[i] - times[picks[j]])
            best = j + 1;
        index[i] = std::uint32_t(best);
    }
    return index;
}

common::LocalMapData merge_local_maps(const common::LocalMapData& into,
                                      const common::LocalMapData& add,
                                      const Eigen::Isometry3d& T_into_add,
                                      std::size_t max_observation_times, double same_surface,
                                      std::size_t* absorbed_count, double beside_surface,
                                      std::size_t* beside_count) {
    common::LocalMapData out;
    out.id = into.id;
    out.revision = into.revision + 1;
    out.finished = into.finished;
    out.segment = into.segment;
    out.T_odom_anchor = into.T_odom_anchor;
    out.T_anchor_grid = into.T_anchor_grid;
    out.voxel_size = into.voxel_size;

    // Observation times: the sorted union, then bounded; old index -> merged index per map.
    std::vector<double> all;
    all.reserve(into.observation_times.size() + add.observation_times.size());
    all.insert(all.end(), into.observation_times.begin(), into.observation_times.end());
    all.insert(all.end(), add.observation_times.begin(), add.observation_times.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    const std::vector<std::uint32_t> bounded = bound_observation_times(
        all, std::min<std::size_t>(max_observation_times, 65536), &out.observation_times);
    auto index_map = [&](const std::vector<double>& times) {
        std::vector<std::uint32_t> m(times.size());
        for (std::size_t i = 0; i < times.size(); ++i) {
            const auto it = std::lower_bound(all.begin(), all.end(), times[i]);
            m[i] = bounded[std::size_t(it - all.begin())];
        }
        return m;
    };
    const std::vector<std::uint32_t> map_into = index_map(into.observation_times);
    const std::vector<std::uint32_t> map_add = index_map(add.observation_times);

    // `add`'s grid frame in `into`'s grid frame.
    const Eigen::Isometry3d T_grid = into.T_anchor_grid.inverse() * T_into_add * add.T_anchor_grid;
    const Eigen::Matrix3f R = T_grid.linear().cast<float>();
    const double g = double(into.voxel_size);

    out.voxels.reserve(into.voxels.size() + add.voxels.size());
    std::unordered_map<Eigen::Vector3i, std::size_t, CellHash> cell;
    cell.reserve(into.voxels.size() + add.voxels.size());
    for (const common::VoxelData& v : into.voxels) {
        common::VoxelData copy = v;
        remap_seen(&copy.life.seen, map_into);
        const auto [it, fresh] = cell.emplace(v.index, out.voxels.size());
        if (fresh) {
            out.voxels.push_back(std::move(copy));
        } else {
            merge_voxel(out.voxels[it->second], copy);
        }
    }
    const std::size_t n_into = out.voxels.size();  // `into`'s voxels, merged among themselves
    std::size_t absorbed = 0, beside = 0;
    for (const common::VoxelData& v : add.voxels) {
        common::VoxelData moved = v;
        const Eigen::Vector3d p = T_grid * v.centre.cast<double>();
        moved.index = Eigen::Vector3i(int(std::floor(p.x() / g)), int(std::floor(p.y() / g)),
                                      int(std::floor(p.z() / g)));
        // The centre, clamped into its cell against rounding at the cell's faces.
        const Eigen::Vector3d lo = moved.index.cast<double>() * g;
        const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(g);
        moved.centre = p.cwiseMax(lo).cwiseMin(hi).cast<float>();
        moved.normal = R * v.normal;
        if (moved.normal.squaredNorm() > 0.0f) moved.normal.normalize();
        remap_seen(&moved.life.seen, map_add);
        if (same_surface > 0.0 && cell.find(moved.index) == cell.end()) {
            // Seen again across a cell face: the existing voxel of that patch takes it, its centre
            // moved onto that voxel's plane and into its cell.
            const long j = same_surface_voxel(out.voxels, n_into, cell, moved, g, same_surface * g);
            if (j >= 0) {
                common::VoxelData& w = out.voxels[std::size_t(j)];
                const Eigen::Vector3d n = w.normal.cast<double>();
                Eigen::Vector3d foot = moved.centre.cast<double>();
                foot -= n.dot(foot - w.centre.cast<double>()) * n;
                const Eigen::Vector3d wlo = w.index.cast<double>() * g;
                moved.centre =
                    foot.cwiseMax(wlo).cwiseMin(wlo + Eigen::Vector3d::Constant(g)).cast<float>();
                moved.index = w.index;
                merge_voxel(w, moved);
                ++absorbed;
                continue;
            }
        }
        if (beside_surface > 0.0 && cell.find(moved.index) == cell.end() &&
            !inside_old_voxels(cell, n_into, moved.index)) {
            const long j =
                same_surface_voxel(out.voxels, n_into, cell, moved, g, beside_surface * g, false);
            if (j >= 0) {
                // The old surface one cell on: adds nothing, but the old voxel was seen today
                // (its life goes on: forget_unseen_voxels).
                common::VoxelLife& life = out.voxels[std::size_t(j)].life;
                life.last_seen = std::max(life.last_seen, moved.life.last_seen);
                add_seen(life.seen, moved.life.seen);
                ++beside;
                continue;
            }
        }
        const auto [it, fresh] = cell.emplace(moved.index, out.voxels.size());
        if (fresh) {
            out.voxels.push_back(std::move(moved));
        } else {
            merge_voxel(out.voxels[it->second], moved);
        }
    }

    if (absorbed_count) *absorbed_count = absorbed;
    if (beside_count) *beside_count = beside;
    out.voxels.shrink_to_fit();  // reserved for both: a merged map is kept for long
    // The box: `into`'s and the corners of `add`'s, in `into`'s grid frame.
    out.bbox_min = into.bbox_min;
    out.bbox_max = into.bbox_max;
    for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d corner((c & 1) ? add.bbox_max.x() : add.bbox_min.x(),
                                     (c & 2) ? add.bbox_max.y() : add.bbox_min.y(),
                                     (c & 4) ? add.bbox_max.z() : add.bbox_min.z());
        const Eigen::Vector3d q = T_grid * corner;
        out.bbox_min = out.bbox_min.cwiseMin(q);
        out.bbox_max = out.bbox_max.cwiseMax(q);
    }
    return out;
}

std::size_t forget_unseen_voxels(common::LocalMapData* map, int after_visits, double visit_gap) {
    if (after_visits <= 0 || map->voxels.empty()) return 0;
    // The visits' first stamps, ascending; a voxel last seen before the K-th last of them has
    // missed K visits.
    std::vector<double> starts;
    const std::vector<double>& t = map->observation_times;
    for (std::size_t i = 0; i < t.size(); ++i) {
        if (i == 0 || t[i] - t[i - 1] > visit_gap) starts.push_back(t[i]);
    }
    if (starts.size() < std::size_t(after_visits)) return 0;
    const double kth_last = starts[starts.size() - std::size_t(after_visits)];
    const std::size_t before = map->voxels.size();
    map->voxels.erase(
        std::remove_if(map->voxels.begin(), map->voxels.end(),
                       [&](const common::VoxelData& v) { return v.life.last_seen < kth_last; }),
        map->voxels.end());
    return before - map->voxels.size();
}

}  // namespace ltm::mapping
