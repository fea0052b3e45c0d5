#pragma once
// Triangle models of the object kinds (internal to the simulator core). Each builder draws in the
// object's local frame: x along its length, y across, z up from the ground (base_z).
#include "simulator/core/mesh.hpp"
#include "simulator/core/objects.hpp"
#include "simulator/core/random.hpp"
#include "simulator/core/terrain.hpp"

namespace ltm::sim::models {

// Context shared by the builders: the object, its size, a generator seeded by the object and
// a builder whose transform is the object's ground pose.
struct ModelContext {
    const ObjectInstance& object;
    const Terrain& terrain;
    Eigen::Vector3d size;
    Rng rng;
    MeshBuilder builder;
};

// Substation equipment (object_models_site.cpp).
void transformer(ModelContext& c);
void gantry(ModelContext& c);
void insulator_column(ModelContext& c);
void busbar(ModelContext& c);
void pole(ModelContext& c);
void cable_tray(ModelContext& c);
void cabinet(ModelContext& c);
void fence(ModelContext& c);

// Buildings, vegetation and vehicles (object_models_town.cpp).
void building(ModelContext& c);
void house(ModelContext& c);
void wall(ModelContext& c);
void hedge(ModelContext& c);
void tree(ModelContext& c);
void car(ModelContext& c);
void van(ModelContext& c);
void container(ModelContext& c);

// A stack of insulator sheds from z0 to z1 at local (x, y) (porcelain).
void insulator_stack(MeshBuilder& b, double x, double y, double z0, double z1, double radius);
// Ground height relative to the object's base_z at local (x, y).
double local_ground(const ModelContext& c, double x, double y);

}  // namespace ltm::sim::models
