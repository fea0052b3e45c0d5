#include "maintenance/core/motion_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace ltm::maintenance {

namespace {

using CellKey = std::uint64_t;

CellKey pack(const Eigen::Vector3i& c) {
    const auto f = [](int v) { return std::uint64_t(std::uint32_t(v) & 0x1fffffu); };
    return (f(c.x()) << 42) | (f(c.y()) << 21) | f(c.z());
}

// A followed cluster: its cells' centres (one per cell, the mean of its points), their index,
// its points (world frame).
struct Cluster {
    std::vector<Eigen::Vector3f> cells;
    std::unordered_map<CellKey, std::uint32_t> index;
    std::vector<Eigen::Vector3f> points;
    Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
    Eigen::Vector3f extent = Eigen::Vector3f::Zero();  // of its cells' box
    // The same object in an earlier kept scan (the newest where it matched), its scan and time.
    Cluster* prev = nullptr;
    const MotionTracker::Scan* prev_scan = nullptr;
    double prev_time = 0.0;
    bool prev_moved = false;  // displaced from prev by at least the slowest speed followed
    bool reported = false;    // its points were returned as moving
};

// c and the earlier clusters it is linked to by displacements, unless reported already: their
// points into out.
void report(Cluster* c, std::vector<Eigen::Vector3f>* out) {
    for (; c && !c->reported; c = c->prev_moved ? c->prev : nullptr) {
        c->reported = true;
        out->insert(out->end(), c->points.begin(), c->points.end());
    }
}

}  // namespace

struct MotionTracker::Scan {
    double time = 0.0;
    Eigen::Isometry3f T_sensor_world = Eigen::Isometry3f::Identity();
    RangeImage image;
    std::unordered_set<CellKey> occupied;  // every cell with a point, ground included
    std::vector<Cluster> clusters;
};

namespace {

class Cells {
  public:
    explicit Cells(double size) : inv_(1.0f / float(size)) {}
    Eigen::Vector3i coords(const Eigen::Vector3f& p) const {
        return (p * inv_).array().floor().cast<int>();
    }
    CellKey key(const Eigen::Vector3f& p) const { return pack(coords(p)); }

  private:
    float inv_;
};

// The nearest cell centre of `c` within one cell of q and within `radius`, or nothing.
const Eigen::Vector3f* nearest(const Cells& cells, const Cluster& c, const Eigen::Vector3f& q,
                               float radius) {
    const Eigen::Vector3i k = cells.coords(q);
    const Eigen::Vector3f* best = nullptr;
    float best_d2 = radius * radius;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const auto it = c.index.find(pack(k + Eigen::Vector3i(dx, dy, dz)));
                if (it == c.index.end()) continue;
                const float d2 = (c.cells[it->second] - q).squaredNorm();
                if (d2 <= best_d2) {
                    best_d2 = d2;
                    best = &c.cells[it->second];
                }
            }
    return best;
}

// Share of a's cells, shifted by `t`, within `radius` of a cell of b.
double matched(const Cells& cells, const Cluster& a, const Cluster& b, const Eigen::Vector3f& t,
               float radius) {
    std::size_t n = 0;
    for (const Eigen::Vector3f& p : a.cells)
        if (nearest(cells, b, p + t, radius)) ++n;
    return a.cells.empty() ? 0.0 : double(n) / double(a.cells.size());
}

// The displacement t with current ≈ earlier + t: nearest-cell iterations from the centroids'.
Eigen::Vector3f align(const Cells& cells, const Cluster& now, const Cluster& before, float radius) {
    Eigen::Vector3f t = now.centroid - before.centroid;
    for (int it = 0; it < 8; ++it) {
        Eigen::Vector3f sum = Eigen::Vector3f::Zero();
        std::size_t n = 0;
        for (const Eigen::Vector3f& c : now.cells) {
            const Eigen::Vector3f q = c - t;
            if (const Eigen::Vector3f* m = nearest(cells, before, q, radius)) {
                sum += q - *m;
                ++n;
            }
        }
        if (n == 0) break;
        const Eigen::Vector3f step = sum / float(n);
        t += step;
        if (step.norm() < 0.01f) break;
    }
    return t;
}

struct Seen {
    std::size_t cells = 0, known = 0, occupied = 0;
};

// What `other` saw of the place of `c`: its cells with a point in them or a return at them
// (occupied), or a beam through them (empty).
Seen seen_in(const MotionConfig& config, const Cells& cells, const Cluster& c,
             const MotionTracker::Scan& other) {
    std::size_t known = 0, occupied = 0;
    const float size = float(config.cell);
    for (const Eigen::Vector3f& x : c.cells) {
        if (other.occupied.count(cells.key(x))) {
            ++known;
            ++occupied;
            continue;
        }
        const Eigen::Vector3f p = other.T_sensor_world * x;
        // A view's margin (maintenance_config.hpp: free_margin, free_margin_per_m): a surface
        // seen at a grazing angle returns beyond its own cell, and is not empty space.
        const float margin = 0.3f + 0.87f * size + 0.01f * p.norm();
        const Visibility v = other.image.classify(p, size, margin);
        if (v == Visibility::kSurface) {
            ++known;
            ++occupied;
        } else if (v == Visibility::kFree) {
            ++known;
        }
    }
    return {c.cells.size(), known, occupied};
}

// Not occupied: at most max_overlap of the cells seen.
bool free_of(const MotionConfig& config, const Seen& s) {
    return double(s.occupied) <= config.max_overlap * double(s.known);
}
// Seen empty: enough of its cells seen, and not occupied.
bool seen_empty(const MotionConfig& config, const Seen& s) {
    return s.known > 0 && double(s.known) >= config.min_known * double(s.cells) &&
           free_of(config, s);
}

// The scan's cells, ground, and clusters of object size.
void build(const MotionConfig& config, const Cells& cells, const std::vector<Eigen::Vector3f>& pts,
           MotionTracker::Scan* scan) {
    struct Acc {
        Eigen::Vector3f mean = Eigen::Vector3f::Zero();  // the sum of its points until all are in
        std::uint32_t n = 0;
        Eigen::Vector3i coords;
        bool ground = false;
    };
    std::unordered_map<CellKey, std::uint32_t> index;
    std::vector<Acc> acc;
    std::vector<std::uint32_t> cell_of(pts.size());
    index.reserve(pts.size() / 2 + 1);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const Eigen::Vector3i c = cells.coords(pts[i]);
        const auto [it, fresh] = index.emplace(pack(c), std::uint32_t(acc.size()));
        if (fresh) {
            acc.emplace_back();
            acc.back().coords = c;
        }
        acc[it->second].mean += pts[i];
        ++acc[it->second].n;
        cell_of[i] = it->second;
    }
    for (Acc& a : acc) a.mean /= float(a.n);  // the points' mean from here on
    scan->occupied.reserve(index.size());
    for (const auto& [key, i] : index) scan->occupied.insert(key);
    // Ground: within ground_height of the ground level of the 3 x 3 column neighbourhood.
    const float inv_col = 1.0f / float(config.ground_column);
    const auto column = [&](int x, int y) {
        return (std::uint64_t(std::uint32_t(x)) << 32) | std::uint64_t(std::uint32_t(y));
    };
    std::unordered_map<std::uint64_t, float> lowest;
    for (const Acc& a : acc) {
        const Eigen::Vector3f m = a.mean;
        const auto k = column(int(std::floor(m.x() * inv_col)), int(std::floor(m.y() * inv_col)));
        const auto [it, fresh] = lowest.emplace(k, m.z());
        if (!fresh) it->second = std::min(it->second, m.z());
    }
    for (Acc& a : acc) {
        const Eigen::Vector3f m = a.mean;
        const int cx = int(std::floor(m.x() * inv_col)), cy = int(std::floor(m.y() * inv_col));
        // The second lowest of the columns' lowest cells (the lowest when only one has cells):
        // a reflection below the ground (points metres under the road) is not its level.
        float low = std::numeric_limits<float>::infinity(), second = low;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const auto it = lowest.find(column(cx + dx, cy + dy));
                if (it == lowest.end()) continue;
                if (it->second < low) {
                    second = low;
                    low = it->second;
                } else {
                    second = std::min(second, it->second);
                }
            }
        if (std::isfinite(second)) low = second;
        a.ground = m.z() - low <= float(config.ground_height);
    }
    // Clusters: non-ground cells within `neighbourhood` cells (twice that vertically: the
    // rings of a far object are farther apart than its columns) whose means are within
    // join_distance horizontally.
    const int n = config.neighbourhood, nz = 2 * config.neighbourhood;
    const float join2 = float(config.join_distance * config.join_distance);
    std::vector<std::uint32_t> label(acc.size(), 0), stack, members;
    std::uint32_t next = 0;
    std::vector<std::vector<std::uint32_t>> groups;
    for (std::uint32_t s = 0; s < acc.size(); ++s) {
        if (acc[s].ground || label[s]) continue;
        label[s] = ++next;
        members.clear();
        stack.assign(1, s);
        bool too_big = false;
        while (!stack.empty()) {
            const std::uint32_t c = stack.back();
            stack.pop_back();
            if (!too_big) members.push_back(c);
            too_big = too_big || members.size() > std::size_t(config.max_cells);
            for (int dz = -nz; dz <= nz; ++dz)
                for (int dy = -n; dy <= n; ++dy)
                    for (int dx = -n; dx <= n; ++dx) {
                        const auto it =
                            index.find(pack(acc[c].coords + Eigen::Vector3i(dx, dy, dz)));
                        if (it == index.end() || acc[it->second].ground || label[it->second])
                            continue;
                        // Cells' points this far apart across the ground are two objects side
                        // by side (a walker beside a hedge), not one.
                        const Eigen::Vector3f gap = acc[c].mean - acc[it->second].mean;
                        if (gap.head<2>().squaredNorm() > join2) continue;
                        label[it->second] = next;
                        stack.push_back(it->second);
                    }
        }
        if (too_big || members.size() < std::size_t(config.min_cells)) {
            groups.emplace_back();
            continue;
        }
        groups.push_back(members);
    }
    std::vector<std::int32_t> cluster_of_label(next + 1, -1);
    for (std::uint32_t g = 0; g < groups.size(); ++g) {
        if (groups[g].empty()) continue;
        Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
        Eigen::Vector3f hi = -lo;
        Cluster c;
        for (std::uint32_t i : groups[g]) {
            const Eigen::Vector3f m = acc[i].mean;
            lo = lo.cwiseMin(m);
            hi = hi.cwiseMax(m);
            c.index.emplace(pack(acc[i].coords), std::uint32_t(c.cells.size()));
            c.cells.push_back(m);
            c.centroid += m;
        }
        const Eigen::Vector3f ext = hi - lo;
        if (std::max(ext.x(), ext.y()) > float(config.max_extent) ||
            ext.z() > float(config.max_height))
            continue;
        c.centroid /= float(c.cells.size());
        c.extent = ext;
        cluster_of_label[label[groups[g].front()]] = std::int32_t(scan->clusters.size());
        scan->clusters.push_back(std::move(c));
    }
    // Its feet: the ground cells in the columns of its cells, at most the ground's height (and
    // a cell) below its lowest cell there. They are not matched, but leave with it (a
    // motorcycle's wheels, a walker's shoes).
    std::unordered_map<CellKey, std::pair<std::int32_t, int>> column_of;  // cluster, lowest z
    for (std::uint32_t g = 0; g < groups.size(); ++g) {
        if (groups[g].empty()) continue;
        const std::int32_t k = cluster_of_label[label[groups[g].front()]];
        if (k < 0) continue;
        for (std::uint32_t i : groups[g]) {
            const Eigen::Vector3i& c = acc[i].coords;
            const auto [it, fresh] =
                column_of.emplace(pack({c.x(), c.y(), 0}), std::pair{k, c.z()});
            if (!fresh) it->second.second = std::min(it->second.second, c.z());
        }
    }
    const int feet = int(std::ceil(config.ground_height / config.cell)) + 1;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        const Acc& a = acc[cell_of[i]];
        if (a.ground) {
            const auto it = column_of.find(pack({a.coords.x(), a.coords.y(), 0}));
            if (it != column_of.end() && a.coords.z() < it->second.second &&
                a.coords.z() >= it->second.second - feet)
                scan->clusters[std::size_t(it->second.first)].points.push_back(pts[i]);
            continue;
        }
        const std::uint32_t l = label[cell_of[i]];
        if (l == 0 || cluster_of_label[l] < 0) continue;
        scan->clusters[std::size_t(cluster_of_label[l])].points.push_back(pts[i]);
    }
}

}  // namespace

MotionTracker::MotionTracker(const MotionConfig& config, const RangeImageConfig& image,
                             double max_range)
    : config_(config), image_(image), max_range_(max_range) {}
MotionTracker::~MotionTracker() = default;
MotionTracker::MotionTracker(MotionTracker&&) noexcept = default;
MotionTracker& MotionTracker::operator=(MotionTracker&&) noexcept = default;

void MotionTracker::clear() { kept_.clear(); }

namespace {
constexpr double kMaxLinkGap = 0.35;  // [s] an object is linked across at most this
}  // namespace

namespace {

// The cluster of `before` that is c displaced rigidly (at least min_match of each within
// match_distance of the other at the displacement, boxes of similar size) by the least, within
// max_speed x lag; nullptr if none. Its displacement in *t.
Cluster* link(const MotionConfig& config, const Cells& cells, const Cluster& c,
              std::vector<Cluster>& before, double lag, MotionStats* stats, float* shift) {
    const float radius = float(config.match_distance);
    const float reach = float(config.max_speed * lag) + 0.5f;
    Cluster* best = nullptr;
    float best_shift = std::numeric_limits<float>::infinity();
    for (Cluster& b : before) {
        if ((c.centroid - b.centroid).norm() > reach) continue;
        const double ratio = double(std::min(c.cells.size(), b.cells.size())) /
                             double(std::max(c.cells.size(), b.cells.size()));
        if (ratio < 0.5) continue;
        // A rigid object keeps its size: boxes within 0.5 m and 30 % on every axis.
        const Eigen::Vector3f d = (c.extent - b.extent).cwiseAbs();
        if ((d.array() > 0.5f + 0.3f * c.extent.cwiseMax(b.extent).array()).any()) continue;
        // ... and its height: its top and bottom within 0.3 m (objects move on the ground).
        if (d.z() > 0.3f + 0.1f * std::max(c.extent.z(), b.extent.z()) ||
            std::abs(c.centroid.z() - b.centroid.z()) > 0.3f)
            continue;
        ++stats->compared;
        const Eigen::Vector3f t = align(cells, c, b, 2.0f * radius);
        if (t.norm() > reach || t.norm() >= best_shift) continue;
        const double m =
            std::min(matched(cells, c, b, -t, radius), matched(cells, b, c, t, radius));
        if (m >= config.min_match) {
            best_shift = t.norm();
            best = &b;
            *shift = t.head<2>().norm();
        }
    }
    return best;
}

}  // namespace

std::vector<Eigen::Vector3f> MotionTracker::add_scan(const std::vector<Eigen::Vector3f>& points,
                                                     const Eigen::Isometry3d& T_world_sensor,
                                                     double time) {
    std::vector<Eigen::Vector3f> out;
    if (!T_world_sensor.matrix().allFinite() || !std::isfinite(time)) return out;
    if (!kept_.empty() && kept_.back()->time > time) kept_.clear();  // time went back
    while (!kept_.empty() && kept_.front()->time < time - config_.max_lag - 1e-6) kept_.pop_front();
    for (auto& k : kept_)  // links into scans gone
        for (Cluster& c : k->clusters)
            if (c.prev && c.prev_time < kept_.front()->time) c.prev = nullptr;
    auto scan = std::make_unique<Scan>();
    scan->time = time;
    scan->T_sensor_world = T_world_sensor.inverse().cast<float>();
    const Eigen::Isometry3f T = T_world_sensor.cast<float>();
    std::vector<Eigen::Vector3f> world, sensor;
    world.reserve(points.size());
    sensor.reserve(points.size());
    const float lo2 = float(image_.min_range * image_.min_range);
    const float hi2 = float(max_range_ * max_range_);
    for (const Eigen::Vector3f& p : points) {
        const float r2 = p.squaredNorm();
        if (!p.allFinite() || r2 < lo2 || r2 > hi2) continue;
        sensor.push_back(p);
        world.push_back(T * p);
    }
    scan->image = RangeImage(image_, sensor);
    const Cells cells(config_.cell);
    build(config_, cells, world, scan.get());
    ++stats_.scans;
    stats_.clusters += scan->clusters.size();
    const float radius = float(config_.match_distance);
    for (Cluster& c : scan->clusters) {
        // The same object in the newest kept scan where it matches (a scan or two back: it may
        // have been joined to something else in one).
        for (auto it = kept_.rbegin(); it != kept_.rend() && !c.prev; ++it) {
            if (time - (*it)->time > kMaxLinkGap) break;
            float shift = 0.0f;
            c.prev = link(config_, cells, c, (*it)->clusters, time - (*it)->time, &stats_, &shift);
            c.prev_scan = it->get();
            c.prev_time = (*it)->time;
            // The slowest speed the displacement test below accepts.
            c.prev_moved =
                double(shift) >= config_.min_shift / config_.max_lag * (time - c.prev_time);
        }
        if (!c.prev) continue;
        if (c.prev->reported && c.prev_moved) {  // moving before, still moving: moving now
            report(&c, &out);
            continue;
        }
        // Its oldest ancestor within max_lag, at least min_lag ago.
        const Cluster* a = &c;
        const MotionTracker::Scan* a_scan = nullptr;
        for (const Cluster* p = &c; p->prev && time - p->prev_time <= config_.max_lag + 1e-6;
             p = p->prev) {
            a = p->prev;
            a_scan = p->prev_scan;
        }
        if (!a_scan || time - a_scan->time < config_.min_lag - 1e-6) continue;
        ++stats_.compared;
        const Eigen::Vector3f t = align(cells, c, *a, 2.0f * radius);
        if (t.head<2>().norm() < float(config_.min_shift)) continue;
        if (std::min(matched(cells, c, *a, -t, radius), matched(cells, *a, c, t, radius)) <
            config_.min_match)
            continue;
        // Its place now was not occupied then, nor its place then now, and one of them was
        // seen empty (the other may be hidden: an object moving along the beams hides its own
        // place ahead of it).
        const Seen now_then = seen_in(config_, cells, c, *a_scan);
        const Seen then_now = seen_in(config_, cells, *a, *scan);
        if (!free_of(config_, now_then) || !free_of(config_, then_now) ||
            !(seen_empty(config_, now_then) || seen_empty(config_, then_now)))
            continue;
        ++stats_.moving;
        report(&c, &out);
    }
    kept_.push_back(std::move(scan));
    return out;
}

std::size_t MotionTracker::memory_bytes() const {
    std::size_t bytes = 0;
    for (const auto& s : kept_) {
        bytes += s->image.memory_bytes() + s->occupied.size() * 24;
        for (const Cluster& c : s->clusters)
            bytes +=
                (c.cells.size() + c.points.size()) * sizeof(Eigen::Vector3f) + c.index.size() * 24;
    }
    return bytes;
}

}  // namespace ltm::maintenance
