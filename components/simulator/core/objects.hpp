#pragma once
// Static scene objects: what they are, where they stand, and their triangle models.
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "simulator/core/geometry2d.hpp"
#include "simulator/core/mesh.hpp"

namespace ltm::sim {

class Terrain;

enum class ObjectKind : std::uint8_t {
    kBuilding,         // flat roof, offices, control buildings, warehouses
    kHouse,            // gable roof
    kTransformer,      // tank, radiators, conservator, bushings
    kGantry,           // portal: two columns and a cross beam
    kInsulatorColumn,  // support column with a porcelain insulator stack
    kBusbar,           // tubular conductor on two insulator columns
    kPole,             // lighting pole with a lamp arm
    kCableTray,        // raised tray on short supports
    kCabinet,          // outdoor control cabinet
    kFence,            // straight run of chain-link fence with posts
    kWall,             // low garden wall
    kHedge,            // porous hedge
    kTree,             // trunk and porous crown
    kCar,
    kVan,
    kContainer,  // 20 ft shipping container
    kCount
};

const char* object_kind_name(ObjectKind kind);
// False when the name is unknown.
bool parse_object_kind(const std::string& name, ObjectKind& kind);
// Default size (length along the heading, width, height) [m].
Eigen::Vector3d default_object_size(ObjectKind kind);
bool is_vehicle(ObjectKind kind);

struct ObjectInstance {
    std::uint32_t id = 0;  // >= 1, stable across sessions
    ObjectKind kind = ObjectKind::kBuilding;
    double x = 0.0, y = 0.0;                         // [m] centre of the footprint
    double yaw = 0.0;                                // [rad] heading of the length axis
    Eigen::Vector3d size = Eigen::Vector3d::Zero();  // [m] length, width, height
    std::uint64_t seed = 0;                          // shape variation
    double base_z = 0.0;  // [m] lowest ground height under the footprint (set at placement)
    double sink = 0.2;    // [m] how far solids reach below base_z (hides slope gaps)
    bool parked = false;  // a parked vehicle: later sessions may move or remove it

    OrientedRect footprint() const;
};

// Appends the object's triangles (object id = instance id) to the mesh.
void build_object(const ObjectInstance& object, const Terrain& terrain, Mesh& mesh);

// Sets base_z and sink from the terrain under the footprint.
void settle_on_terrain(ObjectInstance& object, const Terrain& terrain);

}  // namespace ltm::sim
