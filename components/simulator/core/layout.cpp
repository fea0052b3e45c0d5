#include "simulator/core/layout.hpp"

#include <algorithm>
#include <cmath>

namespace ltm::sim {

bool Layout::try_place(ObjectInstance o, double road_margin, double margin) {
    const OrientedRect r = o.footprint();
    if (!terrain.covered(o.x, o.y)) return false;
    if (!free_space.is_free(r, road_margin, margin)) return false;
    o.id = next_id++;
    settle_on_terrain(o, terrain);
    free_space.add_footprint(r, o.id);
    objects.push_back(o);
    return true;
}

Material Layout::ground_material(const Eigen::Vector2d& p) const {
    if (style == WorldStyle::kTown) {
        const double d = roads.corridor_distance(p, 9.0);
        if (d < 5.8) return Material::kAsphalt;
        if (d < 8.2) return Material::kConcrete;
        return Material::kGrass;
    }
    if (!parking.isEmpty() && parking.contains(p)) return Material::kAsphalt;
    if (roads.corridor_distance(p, road_half + 0.5) <= road_half) return Material::kAsphalt;
    if (!yard.isEmpty() && yard.contains(p)) return Material::kGravel;
    return Material::kGrass;
}

void scatter_trees(Layout& layout, double per_1000_m2, Rng& rng) {
    const Eigen::AlignedBox2d& region = layout.terrain.region();
    const double area = region.sizes().prod();
    const int n = static_cast<int>(area / 1000.0 * per_1000_m2);
    for (int k = 0; k < n; ++k) {
        ObjectInstance o;
        o.kind = rng.chance(0.15) ? ObjectKind::kHedge : ObjectKind::kTree;
        o.x = rng.uniform(region.min().x(), region.max().x());
        o.y = rng.uniform(region.min().y(), region.max().y());
        o.yaw = rng.uniform(0, M_PI);
        const double d = rng.uniform(3.0, 8.0);
        o.size = o.kind == ObjectKind::kTree
                     ? Eigen::Vector3d(d, d, rng.uniform(1.2, 2.0) * d)
                     : Eigen::Vector3d(rng.uniform(4, 12), 1.2, rng.uniform(1.2, 2.2));
        o.seed = rng.next();
        if (!layout.yard.isEmpty() && layout.yard.contains(Eigen::Vector2d(o.x, o.y))) continue;
        const double road_margin = layout.style == WorldStyle::kTown ? 6.0 : 2.0;
        layout.try_place(o, road_margin, 0.5);
    }
}

Layout build_layout(const WorldConfig& config, std::uint64_t seed, const LayoutInputs& in) {
    Layout L;
    L.style = config.style;
    L.road_half = 0.5 * config.road_width;
    Eigen::AlignedBox2d box;
    for (const auto& path : in.robot_paths) {
        for (const auto& p : path) box.extend(p);
    }
    for (const auto& o : config.objects) box.extend(Eigen::Vector2d(o.x, o.y));
    if (config.style == WorldStyle::kSubstation) {
        L.yard = config.substation.yard;
        L.parking = config.substation.parking;
        if (!L.yard.isEmpty()) box.extend(L.yard);
        if (!L.parking.isEmpty()) box.extend(L.parking);
    }
    box.min() -= Eigen::Vector2d::Constant(config.margin);
    box.max() += Eigen::Vector2d::Constant(config.margin);
    L.terrain = Terrain(config.terrain, box, seed);
    if (!in.ground.empty()) L.terrain.anchor(in.ground);
    Points2 samples;
    for (const auto& path : in.robot_paths) {
        const Polyline line(path);
        for (double s = 0; s <= line.length() + 5.0; s += 5.0) samples.push_back(line.point_at(s));
    }
    for (const auto& o : config.objects) samples.emplace_back(o.x, o.y);
    L.terrain.restrict_to(samples, std::min(in.sensor_range, config.margin) + 10.0);

    for (const auto& path : in.robot_paths) {
        L.free_space.add_corridor(path, L.road_half, true);
        L.roads.add_corridor(path, L.road_half, true);
    }
    // Kept clear, but not roads: the site's roads shape its bays and paving.
    for (const auto& path : in.clearings) L.free_space.add_corridor(path, L.road_half, true);
    for (const auto& [path, half_width] : in.actor_paths)
        L.free_space.add_corridor(path, half_width, false);

    for (const auto& p : config.objects) {
        ObjectInstance o;
        o.id = L.next_id++;
        o.kind = p.kind;
        o.x = p.x;
        o.y = p.y;
        o.yaw = p.yaw_deg * M_PI / 180.0;
        o.size = p.size;
        o.parked = p.parked;
        o.seed = hash_mix(seed, o.id);
        settle_on_terrain(o, L.terrain);
        L.free_space.add_footprint(o.footprint(), o.id);
        L.objects.push_back(o);
    }
    Rng rng(hash_mix(seed, 0x1A7007));
    if (config.style == WorldStyle::kSubstation) {
        layout_substation(L, config, in, rng);
    } else {
        layout_town(L, config, in, rng);
    }
    scatter_trees(L, config.tree_density, rng);
    return L;
}

}  // namespace ltm::sim
