// A town along the routes: every route is a street (the robot on its centre line, parking
// lanes, kerbs, pavements with trees and lamp posts, front gardens, houses and blocks behind).
#include <algorithm>
#include <cmath>

#include "simulator/core/layout.hpp"

namespace ltm::sim {
namespace {

// Cross-section of a street, distances from the route centre line [m].
constexpr double kParking = 4.6;   // parallel-parked cars
constexpr double kKerb = 5.8;      // kerb stones
constexpr double kPole = 6.8;      // lamp posts
constexpr double kTree = 7.4;      // street trees
constexpr double kGarden = 8.8;    // front-garden walls, hedges and fences
constexpr double kBuilding = 9.8;  // nearest building front

struct Frame {
    Eigen::Vector2d p, t, left;
    double yaw;
};

Frame frame_at(const Polyline& line, double s) {
    Frame f;
    f.p = line.point_at(s);
    Eigen::Vector2d d = line.point_at(s + 4.0) - line.point_at(s - 4.0);
    f.t = d.norm() > 1e-6 ? Eigen::Vector2d(d.normalized()) : line.tangent_at(s);
    f.left = {-f.t.y(), f.t.x()};
    f.yaw = std::atan2(f.t.y(), f.t.x());
    return f;
}

ObjectInstance make(ObjectKind kind, const Eigen::Vector2d& p, double yaw,
                    const Eigen::Vector3d& size, Rng& rng) {
    ObjectInstance o;
    o.kind = kind;
    o.x = p.x();
    o.y = p.y();
    o.yaw = yaw;
    o.size = size;
    o.seed = rng.next();
    return o;
}

// road_margin is the distance kept from every road's corridor edge (road_half).
double margin_for(const Layout& L, double offset, double half_width) {
    return std::max(0.2, offset - half_width - L.road_half - 0.15);
}

void buildings(Layout& L, const Polyline& line, double side, const TownConfig& c, Rng& rng) {
    for (double s = rng.uniform(0, 8); s < line.length();) {
        const double width = rng.uniform(9.0, 18.0);
        const Frame f = frame_at(line, s + width / 2);
        s += width + rng.uniform(1.0, 4.0);
        const Eigen::Vector2d n = side * f.left;
        if (rng.chance(0.6)) {  // front-garden boundary
            const double u = rng.uniform();
            const ObjectKind kind =
                u < 0.55 ? ObjectKind::kHedge : (u < 0.85 ? ObjectKind::kWall : ObjectKind::kFence);
            const Eigen::Vector3d size =
                kind == ObjectKind::kHedge
                    ? Eigen::Vector3d(width - 1.0, 1.0, rng.uniform(1.0, 2.2))
                : kind == ObjectKind::kWall
                    ? Eigen::Vector3d(width - 1.0, 0.3, rng.uniform(0.6, 1.6))
                    : Eigen::Vector3d(width - 1.0, 0.1, 1.6);
            L.try_place(make(kind, f.p + n * kGarden, f.yaw, size, rng),
                        margin_for(L, kGarden, 0.5 * size.y()), 0.3);
        }
        const double front = kBuilding + rng.uniform(0.0, 4.0);
        const double depth = rng.uniform(8.0, 14.0);
        if (rng.chance(c.building_probability)) {
            const bool house = rng.chance(0.6);
            const Eigen::Vector3d size(width - rng.uniform(0.5, 2.0), depth,
                                       house ? rng.uniform(7.0, 11.0) : rng.uniform(9.0, 18.0));
            const ObjectKind kind = house ? ObjectKind::kHouse : ObjectKind::kBuilding;
            L.try_place(make(kind, f.p + n * (front + depth / 2), f.yaw, size, rng),
                        margin_for(L, front, 0.0), 0.3);
        }
        // Shrubs and small trees in the front garden.
        for (int k = rng.uniform_int(1, 4); k > 0; --k) {
            const double d = rng.uniform(2.0, 6.0);
            const double off = rng.uniform(kGarden + 0.8 + 0.2 * d,
                                           std::max(kGarden + 1.0 + 0.2 * d, front + 2.0));
            const Eigen::Vector2d p = f.p + n * off + f.t * rng.uniform(-0.4, 0.4) * width;
            L.try_place(make(ObjectKind::kTree, p, 0.0, {d, d, rng.uniform(1.0, 2.2) * d}, rng),
                        margin_for(L, off, 0.2 * d), 0.2);
        }
        if (rng.chance(c.second_row_probability)) {
            const double depth2 = rng.uniform(10.0, 20.0);
            const double off2 = front + depth + rng.uniform(4.0, 10.0) + depth2 / 2;
            const Eigen::Vector3d size2(width * rng.uniform(0.8, 1.3), depth2,
                                        rng.uniform(9.0, 22.0));
            L.try_place(make(ObjectKind::kBuilding, f.p + n * off2, f.yaw, size2, rng),
                        margin_for(L, front, 0.0), 0.6);
        }
    }
}

void street(Layout& L, const Points2& path, const TownConfig& c, Rng& rng) {
    const Polyline line(path);
    for (const double side : {-1.0, 1.0}) {
        // Parked cars, recording the empty spaces.
        for (double s = rng.uniform(0, 6); s < line.length(); s += 6.2) {
            const Frame f = frame_at(line, s);
            ObjectInstance v = make(rng.chance(0.85) ? ObjectKind::kCar : ObjectKind::kVan,
                                    f.p + side * f.left * kParking, side > 0 ? f.yaw + M_PI : f.yaw,
                                    Eigen::Vector3d::Zero(), rng);
            v.size = default_object_size(v.kind);
            v.parked = true;
            const double m = margin_for(L, kParking, 0.5 * v.size.y());
            if (rng.chance(c.parked_car_probability)) {
                L.try_place(v, m, 0.3);
            } else if (L.free_space.is_free(v.footprint(), m, 0.3) && L.terrain.covered(v.x, v.y)) {
                L.parking_slots.push_back(v.footprint());
            }
        }
        // Kerbs in 12 m pieces.
        for (double s = 0; s < line.length(); s += 12.0) {
            const Frame f = frame_at(line, s + 6.0);
            L.try_place(make(ObjectKind::kWall, f.p + side * f.left * kKerb, f.yaw,
                             {12.0, 0.25, 0.13}, rng),
                        margin_for(L, kKerb, 0.125), 0.0);
        }
        for (double s = rng.uniform(0, c.tree_spacing); s < line.length();
             s += c.tree_spacing * rng.uniform(0.7, 1.3)) {
            if (!rng.chance(0.85)) continue;
            const Frame f = frame_at(line, s);
            const double d = rng.uniform(5.0, 10.0);  // crown diameter, height 1.4-2.2 times
            const double off = std::max(kTree, kKerb + 0.2 * d + 0.4) + rng.uniform(0.0, 0.6);
            L.try_place(make(ObjectKind::kTree, f.p + side * f.left * off, 0.0,
                             {d, d, rng.uniform(1.4, 2.2) * d}, rng),
                        margin_for(L, off, 0.2 * d), 0.3);
        }
        for (double s = (side > 0 ? 0.5 : 0.0) * c.pole_spacing; s < line.length();
             s += c.pole_spacing) {
            const Frame f = frame_at(line, s);
            L.try_place(make(ObjectKind::kPole, f.p + side * f.left * kPole,
                             f.yaw + (side > 0 ? -M_PI / 2 : M_PI / 2),
                             {0.3, 0.3, rng.uniform(7.0, 9.0)}, rng),
                        margin_for(L, kPole, 0.15), 0.3);
        }
        buildings(L, line, side, c, rng);
    }
}

}  // namespace

void layout_town(Layout& L, const WorldConfig& config, const LayoutInputs& in, Rng& rng) {
    for (const auto& path : in.robot_paths) street(L, path, config.town, rng);
}

}  // namespace ltm::sim
