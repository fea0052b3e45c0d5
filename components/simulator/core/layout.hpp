#pragma once
// The static scene of a world: terrain plus objects, procedural by seed around the routes
// (a substation yard or a town along streets), placed objects first.
#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

#include "simulator/core/free_space.hpp"
#include "simulator/core/objects.hpp"
#include "simulator/core/random.hpp"
#include "simulator/core/scenario.hpp"
#include "simulator/core/terrain.hpp"

namespace ltm::sim {

struct LayoutInputs {
    std::vector<Points2> robot_paths;  // route centre lines, all sessions
    // Driven but shaping nothing: only kept clear of objects (a route's later laps and the legs
    // between them, so that a route driven N times leaves the site as one lap does).
    std::vector<Points2> clearings;
    std::vector<std::pair<Points2, double>> actor_paths;  // path and half width, all sessions
    std::vector<Eigen::Vector3d> ground;  // ground under recorded paths (anchors the terrain)
    double sensor_range = 120.0;          // [m] scenery farther from every route is left out
};

struct Layout {
    WorldStyle style = WorldStyle::kSubstation;
    double road_half = 3.5;  // [m] half the kept-clear road width
    Eigen::AlignedBox2d yard, parking;
    Terrain terrain;
    std::vector<ObjectInstance> objects;      // the first session's scene, ids from 1
    FreeSpace free_space;                     // corridors and object footprints
    FreeSpace roads{10.0};                    // robot routes only
    std::vector<OrientedRect> parking_slots;  // empty places where a vehicle may park later
    std::uint32_t next_id = 1;

    // Places `o` (new id, settled on the terrain) when its footprint stays road_margin off the
    // roads and margin off everything else. False when blocked.
    bool try_place(ObjectInstance o, double road_margin, double margin);
    // Ground material at p (road, pavement, gravel yard, grass).
    Material ground_material(const Eigen::Vector2d& p) const;
};

Layout build_layout(const WorldConfig& config, std::uint64_t seed, const LayoutInputs& inputs);

// Procedural parts (substation_layout.cpp, town_layout.cpp, layout.cpp).
void layout_substation(Layout& layout, const WorldConfig& config, const LayoutInputs& in, Rng& rng);
void layout_town(Layout& layout, const WorldConfig& config, const LayoutInputs& in, Rng& rng);
void scatter_trees(Layout& layout, double per_1000_m2, Rng& rng);

}  // namespace ltm::sim
