// Buildings, vegetation and vehicle models.
#include <algorithm>
#include <cmath>

#include "simulator/core/object_models.hpp"

namespace ltm::sim::models {

using V = Eigen::Vector3d;

namespace {

Material facade(Rng& rng) {
    const double u = rng.uniform();
    return u < 0.4 ? Material::kPlaster : (u < 0.75 ? Material::kBrick : Material::kConcrete);
}

// Pieces of at most `step` metres following the ground (walls, hedges).
template <typename F>
void along_ground(const ModelContext& c, double step, F&& piece) {
    const double L = c.size.x();
    const int n = std::max(1, static_cast<int>(std::ceil(L / step)));
    for (int k = 0; k < n; ++k) {
        const double x0 = -L / 2 + L * k / n, x1 = -L / 2 + L * (k + 1) / n;
        piece(x0, x1, local_ground(c, 0.5 * (x0 + x1), 0));
    }
}

void wheels(MeshBuilder& b, double L, double W, double r) {
    b.set_material(Material::kRubber);
    for (int sx = -1; sx <= 1; sx += 2) {
        for (int sy = -1; sy <= 1; sy += 2) {
            const double x = sx * (L / 2 - 0.85), y = sy * (W / 2 - 0.12);
            b.cylinder(V(x, y - 0.11, r), V(x, y + 0.11, r), r, 10);
        }
    }
}

Material paint(Rng& rng) {
    const double u = rng.uniform();
    return u < 0.4 ? Material::kCarPaintDark
                   : (u < 0.8 ? Material::kCarPaint : Material::kCarPaintLight);
}

}  // namespace

void building(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), H = c.size.z(), s = c.object.sink;
    b.set_material(facade(c.rng));
    b.box(V(-L / 2, -W / 2, -s), V(L / 2, W / 2, H));
    // Parapet, rooftop plant and an entrance canopy.
    for (int side = -1; side <= 1; side += 2) {
        b.box(V(-L / 2, side * W / 2 - 0.15, H), V(L / 2, side * W / 2 + 0.15, H + 0.6));
        b.box(V(side * L / 2 - 0.15, -W / 2, H), V(side * L / 2 + 0.15, W / 2, H + 0.6));
    }
    b.set_material(Material::kPaintedMetal);
    const int units = c.rng.uniform_int(0, 2);
    for (int k = 0; k < units; ++k) {
        const double x = c.rng.uniform(-L / 3, L / 3), y = c.rng.uniform(-W / 4, W / 4);
        b.box(V(x - 1.2, y - 0.8, H), V(x + 1.2, y + 0.8, H + 1.5));
    }
    b.set_material(Material::kConcrete);
    const double ex = c.rng.uniform(-L / 3, L / 3);
    b.box(V(ex - 2.0, -W / 2 - 2.0, 2.8), V(ex + 2.0, -W / 2, 3.1));
    // Pilasters break up long facades.
    for (double x = -L / 2 + 5; x < L / 2 - 2; x += 5.0) {
        b.box(V(x - 0.25, -W / 2 - 0.25, -s), V(x + 0.25, -W / 2, H));
        b.box(V(x - 0.25, W / 2, -s), V(x + 0.25, W / 2 + 0.25, H));
    }
}

void house(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), H = c.size.z(), s = c.object.sink;
    const double eaves = 0.6 * H;
    const bool garage = L > 9.0 && c.rng.chance(0.5);  // a garage within the footprint
    const double x1 = garage ? L / 2 - 3.6 : L / 2;
    b.set_material(facade(c.rng));
    b.box(V(-L / 2, -W / 2, -s), V(x1, W / 2, eaves));
    b.set_material(Material::kRoofTile);
    b.gable_roof(V(-L / 2 - 0.3, -W / 2 - 0.4, eaves), V(x1 + 0.3, W / 2 + 0.4, H));
    b.set_material(Material::kBrick);
    const double cx = c.rng.uniform(-L / 3, x1 - 1.0);
    b.box(V(cx - 0.4, W / 6 - 0.4, eaves), V(cx + 0.4, W / 6 + 0.4, H + 0.6));
    if (garage) {
        b.set_material(Material::kPlaster);
        b.box(V(x1 + 0.3, -W / 2, -s), V(L / 2, -W / 2 + std::min(6.0, W), 2.6));
    }
}

void wall(ModelContext& c) {
    const double W = c.size.y(), H = c.size.z();
    c.builder.set_material(c.rng.chance(0.5) ? Material::kBrick : Material::kConcrete);
    along_ground(c, 3.0, [&](double x0, double x1, double g) {
        c.builder.box(V(x0, -W / 2, g - 0.3), V(x1, W / 2, g + H));
    });
}

void hedge(ModelContext& c) {
    const double W = c.size.y(), H = c.size.z();
    c.builder.set_material(Material::kFoliage);
    along_ground(c, 3.0, [&](double x0, double x1, double g) {
        c.builder.box(V(x0, -W / 2, g - 0.2), V(x1, W / 2, g + H * c.rng.uniform(0.9, 1.1)));
    });
}

void tree(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double D = c.size.x(), H = c.size.z(), s = c.object.sink;
    const double trunk_r = std::clamp(0.04 * D, 0.12, 0.4);
    const bool conifer = c.rng.chance(0.25);
    const double crown_base = conifer ? 0.2 * H : c.rng.uniform(0.3, 0.45) * H;
    b.set_material(Material::kBark);
    b.frustum(V(0, 0, -s), V(0, 0, 0.85 * H), trunk_r, 0.4 * trunk_r, 8);
    b.set_material(Material::kFoliage);
    if (conifer) {
        const int tiers = 3;
        for (int k = 0; k < tiers; ++k) {
            const double z0 = crown_base + (H - crown_base) * k / (tiers + 0.5);
            const double r = 0.5 * D * (1.0 - 0.25 * k);
            b.frustum(V(0, 0, z0), V(0, 0, z0 + (H - crown_base) * 0.45), r, 0.05, 10);
        }
        return;
    }
    const double R = 0.5 * D, crown_h = H - crown_base;
    const int blobs = c.rng.uniform_int(3, 5);
    for (int k = 0; k < blobs; ++k) {
        const double a = c.rng.uniform(0, 2 * M_PI), d = c.rng.uniform(0.0, 0.45) * R;
        const double r = c.rng.uniform(0.55, 0.75) * R;
        const double z = crown_base + c.rng.uniform(0.35, 0.6) * crown_h;
        b.ellipsoid(V(d * std::cos(a), d * std::sin(a), z),
                    V(r, r, 0.5 * crown_h * c.rng.uniform(0.7, 0.9)));
    }
}

void car(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), H = c.size.z();
    wheels(b, L, W, 0.32);
    b.set_material(paint(c.rng));
    b.box(V(-L / 2, -W / 2, 0.28), V(L / 2, W / 2, 0.92));
    const double c0 = -L / 2 + 0.7, c1 = L / 2 - 1.4;  // cabin, shorter at the bonnet
    b.box(V(c0, -W / 2 + 0.08, H - 0.06), V(c1, W / 2 - 0.08, H));
    b.set_material(Material::kGlass);
    b.box(V(c0, -W / 2 + 0.1, 0.92), V(c1, W / 2 - 0.1, H - 0.06));
    b.set_material(Material::kFabric);
    b.box(V(c0 + 0.3, -W / 2 + 0.3, 0.92), V(c1 - 0.3, W / 2 - 0.3, 1.2));
    b.set_material(Material::kRetroreflector);
    b.box(V(L / 2, -0.26, 0.42), V(L / 2 + 0.02, 0.26, 0.53));
    b.box(V(-L / 2 - 0.02, -0.26, 0.55), V(-L / 2, 0.26, 0.66));
}

void van(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), H = c.size.z();
    wheels(b, L, W, 0.36);
    b.set_material(c.rng.chance(0.6) ? Material::kCarPaintLight : Material::kCarPaint);
    b.box(V(-L / 2, -W / 2, 0.35), V(L / 2 - 0.9, W / 2, H));
    b.box(V(L / 2 - 0.9, -W / 2, 0.35), V(L / 2, W / 2, 1.1));
    b.set_material(Material::kGlass);
    b.box(V(L / 2 - 0.9, -W / 2 + 0.1, 1.1), V(L / 2 - 0.3, W / 2 - 0.1, H - 0.3));
    b.set_material(Material::kRetroreflector);
    b.box(V(L / 2, -0.26, 0.45), V(L / 2 + 0.02, 0.26, 0.56));
}

void container(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), H = c.size.z();
    b.set_material(Material::kPaintedMetal);
    b.box(V(-L / 2, -W / 2, 0.1), V(L / 2, W / 2, H));
    for (double x = -L / 2 + 0.4; x < L / 2 - 0.2; x += 0.55) {  // corrugation
        b.box(V(x - 0.08, -W / 2 - 0.03, 0.2), V(x + 0.08, -W / 2, H - 0.1));
        b.box(V(x - 0.08, W / 2, 0.2), V(x + 0.08, W / 2 + 0.03, H - 0.1));
    }
    b.set_material(Material::kSteel);
    for (int sx = -1; sx <= 1; sx += 2) {
        for (int sy = -1; sy <= 1; sy += 2) {
            b.box(V(sx * L / 2 - 0.15, sy * W / 2 - 0.15, -0.2),
                  V(sx * L / 2 + 0.15, sy * W / 2 + 0.15, 0.1));
        }
    }
}

}  // namespace ltm::sim::models
