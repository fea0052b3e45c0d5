#pragma once
// Surface materials: how bright a surface looks to a 905 nm LiDAR and how porous it is.
#include <cstdint>

namespace ltm::sim {

enum class Material : std::uint8_t {
    kAsphalt,
    kGravel,
    kGrass,
    kConcrete,
    kBrick,
    kPlaster,
    kRoofTile,
    kSteel,         // weathered structural steel
    kPaintedMetal,  // cabinets, transformer tanks, containers
    kGalvanized,    // gantries, cable trays, fence posts
    kPorcelain,     // insulators
    kBark,
    kFoliage,    // porous
    kChainLink,  // porous fence mesh
    kCarPaint,
    kCarPaintDark,
    kCarPaintLight,
    kGlass,  // porous (most pulses pass a window)
    kRubber,
    kFabric,          // pedestrians
    kRetroreflector,  // signs, number plates
    kCount
};

struct MaterialProperties {
    const char* name;
    float reflectivity;  // intensity at normal incidence, KITTI-like scale [0, 1]
    float pass;          // probability that a pulse passes the surface (porous ones) [0, 1]
};

const MaterialProperties& material_properties(Material m);

}  // namespace ltm::sim
