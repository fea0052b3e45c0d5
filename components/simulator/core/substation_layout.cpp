// A substation-like site: fenced gravel yard with equipment bays, lighting poles and cable trays
// along the roads, service vehicles, a car park outside, trees around.
#include <algorithm>
#include <cmath>

#include "simulator/core/layout.hpp"

namespace ltm::sim {
namespace {

ObjectInstance make(ObjectKind kind, double x, double y, double yaw, Eigen::Vector3d size,
                    Rng& rng) {
    ObjectInstance o;
    o.kind = kind;
    o.x = x;
    o.y = y;
    o.yaw = yaw;
    o.size = size;
    o.seed = rng.next();
    return o;
}

// Fence along the yard boundary in runs of about `segment` metres; a run crossing a road is cut
// into panel-sized pieces and the ones on the road are left out (gates).
void fence(Layout& L, const SubstationConfig& c, Rng& rng) {
    const Eigen::Vector2d lo = c.yard.min(), hi = c.yard.max();
    const Eigen::Vector2d corners[5] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}, lo};
    for (int side = 0; side < 4; ++side) {
        const Eigen::Vector2d a = corners[side], b = corners[side + 1];
        const double len = (b - a).norm();
        const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());
        const int runs = std::max(1, static_cast<int>(std::round(len / c.fence_segment)));
        for (int r = 0; r < runs; ++r) {
            const double s0 = len * r / runs, s1 = len * (r + 1) / runs;
            const Eigen::Vector2d m = a + (b - a) * (0.5 * (s0 + s1) / len);
            // Runs end 10 cm short of each other (and of the corners), so neighbours do not
            // overlap.
            if (L.try_place(
                    make(ObjectKind::kFence, m.x(), m.y(), yaw, {s1 - s0 - 0.2, 0.1, 2.4}, rng),
                    0.5, 0.0))
                continue;
            const int pieces = std::max(1, static_cast<int>(std::round((s1 - s0) / 3.0)));
            for (int k = 0; k < pieces; ++k) {
                const double t = s0 + (s1 - s0) * (k + 0.5) / pieces;
                const Eigen::Vector2d p = a + (b - a) * (t / len);
                L.try_place(make(ObjectKind::kFence, p.x(), p.y(), yaw,
                                 {(s1 - s0) / pieces - 0.2, 0.1, 2.4}, rng),
                            0.5, 0.0);
            }
        }
    }
}

void line_bay(Layout& L, const SubstationConfig& c, double xc, double w, double y0, double y1,
              Rng& rng) {
    const double gh = rng.uniform(10.0, 13.0);
    for (const double y : {y0 + 2.0, y1 - 2.0}) {
        L.try_place(make(ObjectKind::kGantry, xc, y, 0.0, {w - 5.0, 1.2, gh}, rng), 1.0, 0.3);
    }
    int k = 0;
    for (double y = y0 + 8.0; y < y1 - 7.0; y += 9.0, ++k) {
        for (const double dx : {-3.5, 0.0, 3.5}) {
            if (!rng.chance(c.equipment_density)) continue;
            if (k % 2 == 0) {
                L.try_place(make(ObjectKind::kBusbar, xc + dx, y, M_PI / 2, {7.5, 0.7, 4.6}, rng),
                            1.0, 0.2);
            } else {
                for (const double dy : {-1.3, 1.3}) {
                    L.try_place(make(ObjectKind::kInsulatorColumn, xc + dx, y + dy, 0.0,
                                     {0.7, 0.7, 4.4}, rng),
                                1.0, 0.2);
                }
            }
        }
        if (rng.chance(0.3)) {
            L.try_place(
                make(ObjectKind::kCabinet, xc + 0.5 * w - 2.5, y, M_PI / 2, {1.2, 0.6, 2.0}, rng),
                1.0, 0.3);
        }
    }
}

void transformer_bay(Layout& L, const SubstationConfig& c, double xc, double y0, double y1,
                     Rng& rng) {
    const int n = std::max(1, static_cast<int>((y1 - y0) / 22.0));
    for (int k = 0; k < n; ++k) {
        const double y = y0 + (k + 0.5) * (y1 - y0) / n;
        if (!rng.chance(c.equipment_density)) continue;
        const Eigen::Vector3d size(rng.uniform(5.0, 6.5), rng.uniform(3.0, 3.6),
                                   rng.uniform(5.0, 6.2));
        L.try_place(make(ObjectKind::kTransformer, xc, y, M_PI / 2, size, rng), 1.0, 0.5);
        L.try_place(
            make(ObjectKind::kWall, xc, y + 0.5 * size.x() + 2.5, 0.0, {8.0, 0.3, 5.5}, rng), 1.0,
            0.2);
        L.try_place(make(ObjectKind::kCabinet, xc + 5.5, y, M_PI / 2, {1.6, 0.7, 2.1}, rng), 1.0,
                    0.3);
        for (const double dy : {-6.5, 6.5}) {
            L.try_place(
                make(ObjectKind::kInsulatorColumn, xc - 2.5, y + dy, 0.0, {0.7, 0.7, 4.4}, rng),
                1.0, 0.2);
            L.try_place(
                make(ObjectKind::kInsulatorColumn, xc + 2.5, y + dy, 0.0, {0.7, 0.7, 4.4}, rng),
                1.0, 0.2);
        }
    }
}

void open_bay(Layout& L, double xc, double y0, double y1, Rng& rng) {
    for (double y = y0 + 6.0; y < y1 - 6.0; y += rng.uniform(12.0, 25.0)) {
        L.try_place(make(ObjectKind::kCabinet, xc + rng.uniform(-4, 4), y, rng.uniform(0, M_PI),
                         {1.2, 0.6, 2.0}, rng),
                    1.0, 0.5);
    }
}

// Equipment, lighting, trays and service vehicles along a route (inside the yard or not).
void along_route(Layout& L, const Points2& path, const SubstationConfig& c, Rng& rng) {
    const Polyline line(path);
    int n = 0;
    for (double s = rng.uniform(0, 10); s < line.length(); s += 7.0, ++n) {
        const Eigen::Vector2d p = line.point_at(s), t = line.tangent_at(s);
        const Eigen::Vector2d left(-t.y(), t.x());
        const double yaw = std::atan2(t.y(), t.x());
        const bool in_yard = c.yard.contains(p);
        if (n % 4 == 0) {
            const double side = (n / 4) % 2 ? 1.0 : -1.0;
            const Eigen::Vector2d q = p + left * side * (L.road_half + 1.3);
            L.try_place(
                make(ObjectKind::kPole, q.x(), q.y(), yaw + (side > 0 ? -M_PI / 2 : M_PI / 2),
                     {0.3, 0.3, rng.uniform(8.0, 10.0)}, rng),
                1.0, 0.3);
        }
        if (in_yard && rng.chance(0.25)) {
            const Eigen::Vector2d q = p + left * (L.road_half + 2.4);
            L.try_place(make(ObjectKind::kCableTray, q.x(), q.y(), yaw, {6.5, 0.6, 0.6}, rng), 1.0,
                        0.1);
        }
        const Eigen::Vector2d q = p - left * (L.road_half + 1.6);  // parallel parking, right side
        ObjectInstance v = make(rng.chance(0.5) ? ObjectKind::kVan : ObjectKind::kCar, q.x(), q.y(),
                                yaw, Eigen::Vector3d::Zero(), rng);
        v.parked = true;
        v.size = default_object_size(v.kind);
        if (in_yard && rng.chance(0.12)) {
            L.try_place(v, 0.6, 0.5);
        } else if (L.free_space.is_free(v.footprint(), 0.6, 0.5) &&
                   L.terrain.covered(q.x(), q.y())) {
            L.parking_slots.push_back(v.footprint());
        }
    }
}

void car_park(Layout& L, const SubstationConfig& c, Rng& rng) {
    const Eigen::AlignedBox2d& P = c.parking;
    const double space = 2.7, depth = 5.2, aisle = 6.5;
    // Rows back to back in pairs, an aisle between pairs.
    double y = P.min().y() + depth / 2;
    for (int row = 0; y + depth / 2 <= P.max().y(); ++row, y += depth + (row % 2 ? aisle : 0.0)) {
        for (double x = P.min().x() + space / 2; x + space / 2 <= P.max().x(); x += space) {
            ObjectInstance v =
                make(rng.chance(0.8) ? ObjectKind::kCar : ObjectKind::kVan, x, y,
                     rng.chance(0.5) ? M_PI / 2 : -M_PI / 2, Eigen::Vector3d::Zero(), rng);
            v.size = default_object_size(v.kind);
            v.parked = true;
            if (rng.chance(c.parking_occupancy)) {
                L.try_place(v, 0.3, 0.2);
            } else if (L.free_space.is_free(v.footprint(), 0.3, 0.2)) {
                L.parking_slots.push_back(v.footprint());
            }
        }
    }
}

// Free stretches [a, b] of at least `min_len` along a line of samples (1 m apart).
std::vector<std::pair<double, double>> runs(const std::vector<bool>& free, double start,
                                            double min_len) {
    std::vector<std::pair<double, double>> out;
    std::size_t i = 0;
    while (i < free.size()) {
        if (!free[i]) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j + 1 < free.size() && free[j + 1]) ++j;
        if (static_cast<double>(j - i) >= min_len)
            out.emplace_back(start + static_cast<double>(i), start + static_cast<double>(j));
        i = j + 1;
    }
    return out;
}

// Bays between the roads: columns of the yard that no road runs along, cut into bays of about
// bay_width; each bay into the stretches along y that no road crosses.
void bays(Layout& L, const SubstationConfig& c, Rng& rng) {
    const double x0 = c.yard.min().x() + 4.0, x1 = c.yard.max().x() - 4.0;
    const double y0 = c.yard.min().y() + 4.0, y1 = c.yard.max().y() - 4.0;
    std::vector<bool> column_free;
    for (double x = x0; x <= x1; x += 1.0) {
        int blocked = 0, n = 0;
        for (double y = y0; y <= y1; y += 2.0, ++n)
            blocked += !L.roads.is_free({{x, y}, {0.5, 1.0}, 0.0}, 1.0, 0.0);
        column_free.push_back(blocked < 0.3 * n);
    }
    int buildings = 0;
    for (const auto& [xa, xb] : runs(column_free, x0, 10.0)) {
        const int n = std::max(1, static_cast<int>(std::round((xb - xa) / c.bay_width)));
        const double w = (xb - xa) / n;
        for (int b = 0; b < n; ++b) {
            const double xc = xa + (b + 0.5) * w;
            std::vector<bool> row_free;
            for (double y = y0; y <= y1; y += 1.0)
                row_free.push_back(L.roads.is_free({{xc, y}, {0.5 * w - 1.0, 0.5}, 0.0}, 1.0, 0.0));
            for (const auto& [ya, yb] : runs(row_free, y0, 18.0)) {
                const double u = rng.uniform();
                if (u < 0.5) {
                    line_bay(L, c, xc, w, ya, yb, rng);
                } else if (u < 0.82) {
                    transformer_bay(L, c, xc, ya, yb, rng);
                } else if (u < 0.94 && buildings < 2 && w > 12.0) {
                    const Eigen::Vector3d size(w - 4.0, std::min(yb - ya - 2.0, rng.uniform(9, 14)),
                                               rng.uniform(4.5, 7.0));
                    if (L.try_place(
                            make(ObjectKind::kBuilding, xc, 0.5 * (ya + yb), 0.0, size, rng), 1.5,
                            1.0))
                        ++buildings;
                    open_bay(L, xc, ya, yb, rng);
                } else {
                    open_bay(L, xc, ya, yb, rng);
                }
            }
        }
    }
}

}  // namespace

void layout_substation(Layout& L, const WorldConfig& config, const LayoutInputs& in, Rng& rng) {
    const SubstationConfig& c = config.substation;
    if (!c.yard.isEmpty()) fence(L, c, rng);
    for (const auto& path : in.robot_paths) along_route(L, path, c, rng);
    if (!c.parking.isEmpty()) car_park(L, c, rng);
    if (!c.yard.isEmpty()) {
        bays(L, c, rng);
        // A row of trees outside the fence.
        const Eigen::Vector2d lo = c.yard.min() - Eigen::Vector2d::Constant(5.0);
        const Eigen::Vector2d hi = c.yard.max() + Eigen::Vector2d::Constant(5.0);
        for (double s = 0; s < 2 * (hi - lo).sum(); s += rng.uniform(6.0, 12.0)) {
            double u = s;
            Eigen::Vector2d p;
            const double w = hi.x() - lo.x(), h = hi.y() - lo.y();
            if (u < w)
                p = {lo.x() + u, lo.y()};
            else if ((u -= w) < h)
                p = {hi.x(), lo.y() + u};
            else if ((u -= h) < w)
                p = {hi.x() - u, hi.y()};
            else
                p = {lo.x(), hi.y() - (u - w)};
            const double d = rng.uniform(4.0, 7.0);
            L.try_place(
                make(ObjectKind::kTree, p.x(), p.y(), 0.0, {d, d, rng.uniform(1.3, 2.0) * d}, rng),
                2.0, 0.5);
        }
    }
}

}  // namespace ltm::sim
