#pragma once
// Per-point label files and what counts as dynamic.
//
// File: `labels/NNNNNN.label` beside `velodyne/NNNNNN.bin`, one little-endian uint32 a point, in
// the scan's point order (the SemanticKITTI layout).
//
// Encoding (both schemes): bits 0-15 = class, bits 16-31 = object (instance) id.
//
// ltm simulator classes (this header is the contract the simulator writes to):
//   0 kSimNone          no label (not used for returns; reserved)
//   1 kSimStatic        static scene: terrain, buildings, equipment, fences, trees, and parked
//                       objects unchanged between sessions; object id 0 for terrain
//   2 kSimMovingActor   a moving vehicle or pedestrian (object id = actor id, >= 1)
//   3 kSimChangedObject an object that differs between sessions (moved, removed or added
//                       parked vehicle, container, fence segment), static within its session
//                       (object id = the object's id, the same id in every session)
//
// SemanticKITTI: classes 252-259 are the moving ones (moving car, bicyclist, person,
// motorcyclist, on-rails, bus, truck, other-vehicle); everything else is static.
#include <cstdint>

namespace ltm::common {

constexpr std::uint16_t kSimNone = 0;
constexpr std::uint16_t kSimStatic = 1;
constexpr std::uint16_t kSimMovingActor = 2;
constexpr std::uint16_t kSimChangedObject = 3;

inline std::uint16_t label_class(std::uint32_t label) {
    return static_cast<std::uint16_t>(label & 0xFFFFu);
}
inline std::uint16_t label_object_id(std::uint32_t label) {
    return static_cast<std::uint16_t>(label >> 16);
}
inline std::uint32_t make_label(std::uint16_t cls, std::uint16_t object_id) {
    return (static_cast<std::uint32_t>(object_id) << 16) | cls;
}

enum class LabelScheme { kLtmSim, kSemanticKitti };

// True for points the dynamic-removal metric counts as dynamic. With the simulator scheme,
// changed objects count as dynamic only when `changed_is_dynamic` (a multi-session map);
// within one session they are static.
inline bool is_dynamic_label(std::uint32_t label, LabelScheme scheme,
                             bool changed_is_dynamic = false) {
    const std::uint16_t c = label_class(label);
    if (scheme == LabelScheme::kSemanticKitti) return c >= 252 && c <= 259;
    return c == kSimMovingActor || (changed_is_dynamic && c == kSimChangedObject);
}

}  // namespace ltm::common
