// Substation equipment models: plain solids sized like the real thing.
#include <algorithm>
#include <cmath>

#include "simulator/core/object_models.hpp"

namespace ltm::sim::models {

using V = Eigen::Vector3d;

void transformer(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), H = c.size.z();
    const double s = c.object.sink, plinth = 0.3, tank_h = 0.55 * H;
    b.set_material(Material::kConcrete);
    b.box(V(-L / 2 - 0.6, -W / 2 - 1.0, -s), V(L / 2 + 0.6, W / 2 + 1.0, plinth));
    b.set_material(Material::kPaintedMetal);
    const double top = plinth + tank_h;
    b.box(V(-L / 2, -W / 2, plinth), V(L / 2, W / 2, top));
    // Radiator fins along both long sides.
    const int fins = std::max(4, static_cast<int>(0.6 * L / 0.35));
    for (int side = -1; side <= 1; side += 2) {
        for (int k = 0; k < fins; ++k) {
            const double x = -0.3 * L + 0.6 * L * (k + 0.5) / fins;
            const double y0 = side * W / 2, y1 = side * (W / 2 + 0.8);
            b.box(V(x - 0.03, std::min(y0, y1), plinth + 0.3),
                  V(x + 0.03, std::max(y0, y1), top - 0.2));
        }
    }
    // Conservator tank on two supports.
    const double cz = top + 0.9;
    b.box(V(-0.3 * L, -0.1, top), V(-0.3 * L + 0.15, 0.1, cz));
    b.box(V(0.2 * L, -0.1, top), V(0.2 * L + 0.15, 0.1, cz));
    b.cylinder(V(-0.38 * L, -0.0, cz), V(0.3 * L, 0.0, cz), 0.4, 12);
    // High-voltage bushings on one side, low-voltage on the other.
    for (int k = -1; k <= 1; ++k) {
        insulator_stack(b, 0.25 * L * k, W * 0.25, top, H, 0.2);
        insulator_stack(b, 0.25 * L * k, -W * 0.3, top, top + 0.7, 0.12);
    }
}

void gantry(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), H = c.size.z(), s = c.object.sink;
    b.set_material(Material::kConcrete);
    for (int side = -1; side <= 1; side += 2) {
        const double x = side * L / 2;
        const double g = local_ground(c, x, 0);
        b.box(V(x - 0.6, -0.6, g - 0.3 - s), V(x + 0.6, 0.6, g + 0.3));
    }
    b.set_material(Material::kGalvanized);
    for (int side = -1; side <= 1; side += 2) {
        const double x = side * L / 2;
        const double g = local_ground(c, x, 0);
        // Lattice column: four corner legs and braces.
        for (int cx = -1; cx <= 1; cx += 2) {
            for (int cy = -1; cy <= 1; cy += 2) {
                b.box(V(x + cx * 0.25 - 0.05, cy * 0.25 - 0.05, g),
                      V(x + cx * 0.25 + 0.05, cy * 0.25 + 0.05, H));
            }
        }
        for (double z = g + 1.5; z < H - 0.5; z += 2.0) {
            b.box(V(x - 0.3, -0.3, z), V(x + 0.3, 0.3, z + 0.08));
        }
    }
    b.box(V(-L / 2 - 0.3, -0.3, H - 0.7), V(L / 2 + 0.3, 0.3, H));
    b.box(V(-L / 2 - 0.3, -0.3, H - 1.6), V(L / 2 + 0.3, 0.3, H - 1.45));
    // Insulator strings hanging from the beam.
    for (int k = -1; k <= 1; ++k) insulator_stack(b, 0.28 * L * k, 0.0, H - 3.0, H - 0.7, 0.13);
}

void insulator_column(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double H = c.size.z(), s = c.object.sink;
    b.set_material(Material::kConcrete);
    b.cylinder(V(0, 0, -s), V(0, 0, 0.5), 0.32, 8);
    b.set_material(Material::kGalvanized);
    const double support = std::max(1.0, H - 1.6);
    b.cylinder(V(0, 0, 0.5), V(0, 0, support), 0.13, 8);
    insulator_stack(b, 0, 0, support, H - 0.1, 0.2);
    b.set_material(Material::kSteel);
    b.box(V(-0.15, -0.15, H - 0.1), V(0.15, 0.15, H));
}

void busbar(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), H = c.size.z();
    for (int side = -1; side <= 1; side += 2) {
        const double x = side * (L / 2 - 0.3);
        const double g = local_ground(c, x, 0);
        b.set_material(Material::kConcrete);
        b.cylinder(V(x, 0, g - 0.3 - c.object.sink), V(x, 0, g + 0.5), 0.3, 8);
        b.set_material(Material::kGalvanized);
        b.cylinder(V(x, 0, g + 0.5), V(x, 0, H - 1.5), 0.12, 8);
        insulator_stack(b, x, 0, H - 1.5, H - 0.1, 0.18);
    }
    b.set_material(Material::kGalvanized);
    b.cylinder(V(-L / 2, 0, H), V(L / 2, 0, H), 0.07, 8);
}

void pole(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double H = c.size.z(), s = c.object.sink;
    b.set_material(Material::kGalvanized);
    b.frustum(V(0, 0, -s), V(0, 0, H), 0.12, 0.07, 8);
    b.box(V(0, -0.04, H - 0.3), V(1.4, 0.04, H - 0.2));
    b.set_material(Material::kPaintedMetal);
    b.box(V(1.1, -0.15, H - 0.45), V(1.7, 0.15, H - 0.25));
    if (c.rng.chance(0.3)) {  // a traffic sign
        b.set_material(Material::kRetroreflector);
        b.box(V(-0.35, 0.12, 2.2), V(0.35, 0.15, 2.9));
    }
}

void cable_tray(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), lift = 0.45;
    const int pieces = std::max(1, static_cast<int>(std::ceil(L / 3.0)));
    for (int k = 0; k < pieces; ++k) {
        const double x0 = -L / 2 + L * k / pieces, x1 = -L / 2 + L * (k + 1) / pieces;
        const double g = local_ground(c, 0.5 * (x0 + x1), 0);
        b.set_material(Material::kConcrete);
        b.box(V(x0 + 0.05, -W / 2 - 0.05, g - 0.2), V(x0 + 0.25, W / 2 + 0.05, g + lift));
        b.set_material(Material::kGalvanized);
        b.box(V(x0, -W / 2, g + lift), V(x1, W / 2, g + lift + 0.12));
    }
}

void cabinet(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), W = c.size.y(), H = c.size.z(), s = c.object.sink;
    b.set_material(Material::kConcrete);
    b.box(V(-L / 2 - 0.1, -W / 2 - 0.1, -s), V(L / 2 + 0.1, W / 2 + 0.1, 0.15));
    b.set_material(Material::kPaintedMetal);
    b.box(V(-L / 2, -W / 2, 0.15), V(L / 2, W / 2, H));
    b.box(V(-L / 2 - 0.05, -W / 2 - 0.08, H), V(L / 2 + 0.05, W / 2 + 0.08, H + 0.05));
}

void fence(ModelContext& c) {
    MeshBuilder& b = c.builder;
    const double L = c.size.x(), H = c.size.z();
    const int panels = std::max(1, static_cast<int>(std::round(L / 2.8)));
    for (int k = 0; k <= panels; ++k) {
        const double x = -L / 2 + L * k / panels;
        const double g = local_ground(c, x, 0);
        b.set_material(Material::kGalvanized);
        b.cylinder(V(x, 0, g - 0.4), V(x, 0, g + H), 0.04, 6);
        if (k == panels) break;
        const double xn = -L / 2 + L * (k + 1) / panels;
        const double gn = local_ground(c, xn, 0);
        b.cylinder(V(x, 0, g + H - 0.05), V(xn, 0, gn + H - 0.05), 0.025, 6, false);
        b.set_material(Material::kChainLink);
        b.quad(V(x, 0, g - 0.05), V(xn, 0, gn - 0.05), V(xn, 0, gn + H - 0.1),
               V(x, 0, g + H - 0.1));
    }
}

}  // namespace ltm::sim::models
