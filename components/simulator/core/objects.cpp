#include "simulator/core/objects.hpp"

#include <array>
#include <cmath>

#include "simulator/core/object_models.hpp"
#include "simulator/core/terrain.hpp"

namespace ltm::sim {
namespace {

struct KindInfo {
    const char* name;
    double length, width, height;  // default size [m]
};

constexpr std::array<KindInfo, static_cast<int>(ObjectKind::kCount)> kKinds{{
    {"building", 20.0, 12.0, 8.0},
    {"house", 11.0, 9.0, 7.5},
    {"transformer", 5.0, 3.2, 5.5},
    {"gantry", 14.0, 0.6, 12.0},
    {"insulator_column", 0.6, 0.6, 4.5},
    {"busbar", 8.0, 0.6, 4.5},
    {"pole", 0.3, 0.3, 9.0},
    {"cable_tray", 12.0, 0.6, 0.6},
    {"cabinet", 1.2, 0.6, 2.0},
    {"fence", 18.0, 0.1, 2.4},
    {"wall", 10.0, 0.3, 1.2},
    {"hedge", 10.0, 1.0, 1.6},
    {"tree", 5.0, 5.0, 9.0},
    {"car", 4.5, 1.8, 1.5},
    {"van", 5.4, 2.0, 2.3},
    {"container", 6.06, 2.44, 2.59},
}};

bool is_tilted_with_ground(ObjectKind k) { return is_vehicle(k) || k == ObjectKind::kContainer; }

}  // namespace

const char* object_kind_name(ObjectKind kind) { return kKinds[static_cast<int>(kind)].name; }

bool parse_object_kind(const std::string& name, ObjectKind& kind) {
    for (int k = 0; k < static_cast<int>(ObjectKind::kCount); ++k) {
        if (name == kKinds[k].name) {
            kind = static_cast<ObjectKind>(k);
            return true;
        }
    }
    return false;
}

Eigen::Vector3d default_object_size(ObjectKind kind) {
    const KindInfo& k = kKinds[static_cast<int>(kind)];
    return {k.length, k.width, k.height};
}

bool is_vehicle(ObjectKind kind) { return kind == ObjectKind::kCar || kind == ObjectKind::kVan; }

OrientedRect ObjectInstance::footprint() const {
    const Eigen::Vector3d s = size.minCoeff() > 0 ? size : default_object_size(kind);
    OrientedRect r;
    r.center = {x, y};
    r.yaw = yaw;
    r.half = 0.5 * s.head<2>();
    if (kind == ObjectKind::kTree) r.half *= 0.4;  // crowns may overhang
    return r;
}

void settle_on_terrain(ObjectInstance& object, const Terrain& terrain) {
    if (is_tilted_with_ground(object.kind)) {
        object.base_z = terrain.height(object.x, object.y);
        object.sink = 0.0;
        return;
    }
    const Eigen::Vector2d range = terrain.height_range(object.footprint());
    object.base_z = range.x();
    object.sink = range.y() - range.x() + 0.2;
}

void build_object(const ObjectInstance& object, const Terrain& terrain, Mesh& mesh) {
    const Eigen::Vector3d size =
        object.size.minCoeff() > 0 ? object.size : default_object_size(object.kind);
    models::ModelContext c{object, terrain, size, Rng(hash_mix(object.seed, object.id)),
                           MeshBuilder(mesh)};
    Eigen::Isometry3d pose = ground_pose(object.x, object.y, object.base_z, object.yaw);
    if (is_tilted_with_ground(object.kind)) {
        const Eigen::Vector3d n = terrain.normal(object.x, object.y);
        pose.linear() =
            Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n) * pose.linear();
    }
    c.builder.set_transform(pose);
    c.builder.set_object(object.id);
    using K = ObjectKind;
    switch (object.kind) {
        case K::kBuilding:
            models::building(c);
            break;
        case K::kHouse:
            models::house(c);
            break;
        case K::kTransformer:
            models::transformer(c);
            break;
        case K::kGantry:
            models::gantry(c);
            break;
        case K::kInsulatorColumn:
            models::insulator_column(c);
            break;
        case K::kBusbar:
            models::busbar(c);
            break;
        case K::kPole:
            models::pole(c);
            break;
        case K::kCableTray:
            models::cable_tray(c);
            break;
        case K::kCabinet:
            models::cabinet(c);
            break;
        case K::kFence:
            models::fence(c);
            break;
        case K::kWall:
            models::wall(c);
            break;
        case K::kHedge:
            models::hedge(c);
            break;
        case K::kTree:
            models::tree(c);
            break;
        case K::kCar:
            models::car(c);
            break;
        case K::kVan:
            models::van(c);
            break;
        case K::kContainer:
            models::container(c);
            break;
        case K::kCount:
            break;
    }
}

namespace models {

double local_ground(const ModelContext& c, double x, double y) {
    const double cs = std::cos(c.object.yaw), sn = std::sin(c.object.yaw);
    return c.terrain.height(c.object.x + cs * x - sn * y, c.object.y + sn * x + cs * y) -
           c.object.base_z;
}

void insulator_stack(MeshBuilder& b, double x, double y, double z0, double z1, double radius) {
    b.set_material(Material::kPorcelain);
    b.cylinder({x, y, z0}, {x, y, z1}, 0.45 * radius, 8, false);
    const int sheds = std::max(2, static_cast<int>((z1 - z0) / 0.3));
    for (int k = 0; k < sheds; ++k) {
        const double z = z0 + (z1 - z0) * (k + 0.5) / sheds;
        b.frustum({x, y, z - 0.04}, {x, y, z + 0.04}, radius, 0.6 * radius, 10);
    }
}

}  // namespace models
}  // namespace ltm::sim
