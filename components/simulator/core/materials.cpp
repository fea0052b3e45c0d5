#include "simulator/core/materials.hpp"

#include <array>

namespace ltm::sim {
namespace {

// Reflectivities are the intensities KITTI's HDL-64E reports for near surfaces (SemanticKITTI 00:
// road 0.25, sidewalk 0.31, vegetation 0.34, buildings 0.42, cars mostly under 0.1);
// porosity is the chance a pulse passes one crossing of the surface.
constexpr std::array<MaterialProperties, static_cast<int>(Material::kCount)> kTable{{
    {"asphalt", 0.29f, 0.0f},         {"gravel", 0.33f, 0.0f},
    {"grass", 0.40f, 0.0f},           {"concrete", 0.35f, 0.0f},
    {"brick", 0.42f, 0.0f},           {"plaster", 0.52f, 0.0f},
    {"roof_tile", 0.30f, 0.0f},       {"steel", 0.28f, 0.0f},
    {"painted_metal", 0.38f, 0.0f},   {"galvanized", 0.50f, 0.0f},
    {"porcelain", 0.42f, 0.0f},       {"bark", 0.30f, 0.0f},
    {"foliage", 0.43f, 0.3f},         {"chain_link", 0.40f, 0.70f},
    {"car_paint", 0.10f, 0.0f},       {"car_paint_dark", 0.03f, 0.0f},
    {"car_paint_light", 0.25f, 0.0f}, {"glass", 0.02f, 0.65f},
    {"rubber", 0.03f, 0.0f},          {"fabric", 0.30f, 0.0f},
    {"retroreflector", 0.95f, 0.0f},
}};

}  // namespace

const MaterialProperties& material_properties(Material m) {
    return kTable[static_cast<std::size_t>(m)];
}

}  // namespace ltm::sim
